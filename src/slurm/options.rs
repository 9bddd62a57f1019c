//! The command-line options of a submission, shared by `settle run --slurm` and
//! `settle sweep --slurm N`.

/// How to submit (with `--slurm`).
#[derive(clap::Args, Clone, Debug, Default)]
pub struct Submit {
    /// With --slurm: wait until the job (a sweep's merge job) ends, and exit with its exit code.
    #[arg(long, requires = "slurm")]
    pub wait: bool,
    /// With --slurm: an sbatch option added to every job script, e.g.
    /// --sbatch-arg=--partition=short or --sbatch-arg=--account=geo (repeatable); a --time or
    /// --mem given here replaces the one from the cost estimate.
    #[arg(
        long,
        value_name = "ARG",
        allow_hyphen_values = true,
        requires = "slurm"
    )]
    pub sbatch_arg: Vec<String>,
    /// With --slurm: write the job scripts and print the sbatch commands, without submitting.
    #[arg(long, requires = "slurm", conflicts_with = "wait")]
    pub no_submit: bool,
}

/// The options of a submission that the job's own command must not repeat.
pub const WITH_VALUE: &[&str] = &["--slurm", "--sbatch-arg"];
/// The flags of a submission that the job's own command must not repeat.
pub const FLAGS: &[&str] = &["--wait", "--no-submit"];
