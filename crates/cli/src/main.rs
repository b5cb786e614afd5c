//! `sctl`: the command-line front end of the semi-calibrated T-Linkage
//! pipeline; everything is in [`sctl::cli`].

fn main() -> std::process::ExitCode {
    sctl::cli::main()
}
