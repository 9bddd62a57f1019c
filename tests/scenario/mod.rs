//! `src/scenario/`: loading and validating scenarios and their input files.

mod bad_input;
mod outputs_docs;
mod reference_csv;
