//! `settle`: see `settle --help`.

fn main() {
    std::process::exit(settle::cli_main());
}
