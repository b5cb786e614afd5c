//! `sctl`: the command-line front end of the semi-calibrated T-Linkage
//! pipeline; everything is in [`bench::cli`].

fn main() -> std::process::ExitCode {
    bench::cli::main()
}
