//! Studies on a Slurm cluster, submitted by settle itself.
//!
//! - `settle sweep S.toml … --slurm N` ([`sweep()`]): an N-task job array (task `i` runs
//!   `settle sweep S.toml … --shard i/N`, the exact binary and arguments) and a merge job that
//!   depends on it (`afterok`), both written into the sweep's folder (`OUT/<name>_sweep/`, or
//!   `_vary/`) and submitted with `sbatch --parsable`; `--wait` blocks until the merge job ends
//!   and exits with its exit code. Each task asks for the time and memory of the cost estimate
//!   of its cases ([`script::Resources`]).
//! - `settle run S.toml --slurm` ([`run()`]): one job that survives its time limit and
//!   preemption: `--requeue` and `--signal=B:USR1@W`; on the warning the job script asks settle
//!   to stop (SIGTERM: it checkpoints and exits with 130) and requeues the job, which resumes
//!   from the checkpoint (`settle run --resume OUT`), with outputs identical to an uninterrupted
//!   run.
//!
//! `--sbatch-arg ARG` (repeatable) adds `#SBATCH ARG` to every script (partition, account,
//! time, memory: the user's `--time`/`--mem` replace the estimate's); `--no-submit` writes the
//! scripts and prints the `sbatch` commands without submitting. See `docs/cluster.md`.
//!
//! | file | job |
//! |---|---|
//! | `options.rs` | the command-line options shared by `run` and `sweep` ([`Submit`]) |
//! | `script.rs` | the text of a batch script, time and memory from an estimate; pure |
//! | `submit.rs` | writing scripts (only over settle's own), `sbatch`, waiting |
//! | `sweep.rs` | `settle sweep --slurm N` |
//! | `run.rs` | `settle run --slurm` |

pub(crate) mod options;
pub(crate) mod run;
pub(crate) mod script;
pub(crate) mod submit;
pub(crate) mod sweep;

pub(crate) use options::Submit;
pub(crate) use run::run;
pub(crate) use sweep::sweep;
