//! Regression tests: one file `issue_<N>_<slug>.rs` per fixed item of an issue, opening with the
//! symptom as found. Each fails on the old behaviour (set `SETTLE_BIN` to the old binary to see it
//! where the test spawns the binary).

mod issue_12_accepted_silently;
mod issue_12_cost_guard;
mod issue_12_interrupt_free_settling;
mod issue_12_interrupt_sedimentation;
mod issue_12_interrupt_sweep;
mod issue_12_out_dot_keeps_foreign_folder;
mod issue_12_rerun_keeps_user_files;
mod issue_12_reserved_names;
#[cfg(unix)]
mod issue_12_resume_bench_any_dir;
mod issue_12_sample_csv_read_up_front;
mod issue_12_stale_staging;
mod issue_12_sweep_bad_options;
mod issue_12_sweep_unsweepable_kind;
mod issue_13_console_tables;
mod issue_13_run_toml_rerun;
mod issue_13_vary_any_key;
#[cfg(unix)]
mod issue_26_bench_keeps_user_csv;
mod issue_26_fit_ctrl_c;
mod issue_26_invert_ctrl_c;
mod issue_26_readings_collision;
mod issue_26_run_keeps_sweep_folder;
mod issue_26_tilt_ctrl_c;
mod issue_8_concurrent_checkpoint_saves;
