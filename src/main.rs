//! The `specgen` command line: flags → the library → files and an exit code.

mod cli;

fn main() {
    std::process::exit(cli::main());
}
