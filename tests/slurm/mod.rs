//! Studies on a real Slurm (issue 27): the one-node Slurm of `scripts/slurm_local.sh`, which
//! `scripts/test.sh` starts before the tests and stops after them. Without a Slurm that answers,
//! every test here FAILS with a message saying how to start it: they are never skipped.
//!
//! - `sweep.rs`: `settle sweep --slurm 16 --wait` (a job array and its merge job) equals the
//!   local sweep; a failed task is reported by the merge and rerun from the printed command;
//! - `run.rs`: `settle run --slurm` of a sedimentation cylinder whose time limit is shorter than
//!   its run: signalled before the limit, checkpointed, requeued and resumed, byte for byte the
//!   uninterrupted run.

mod run;
mod sweep;

use std::process::Command;

/// Panics with how to start Slurm unless a controller answers with an idle or busy node.
pub fn require_slurm() {
    let o = Command::new("sinfo").args(["-h", "-o", "%T"]).output();
    let up = match &o {
        Ok(o) => {
            let s = String::from_utf8_lossy(&o.stdout);
            o.status.success()
                && s.lines()
                    .any(|l| ["idle", "mixed", "allocated", "completing"].contains(&l.trim()))
        }
        Err(_) => false,
    };
    assert!(
        up,
        "no Slurm answers here (sinfo: {:?}): the tests of tests/slurm/ need one; install \
         Debian's slurm-wlm and munge and run `scripts/slurm_local.sh start` as root \
         (scripts/test.sh does both's second, .ci/run the first)",
        o.as_ref()
            .map(|o| String::from_utf8_lossy(&o.stderr).into_owned())
    );
}
