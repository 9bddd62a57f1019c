//! Unit tests of the scenes' shared parts (moved from `tests/regression/`): the cost guard.

mod issue_17_cylinder_cost_estimate;
