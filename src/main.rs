//! The `specgen` command line: flags → the library → files and an exit code.

mod cli;

fn main() {
    specgen::process::exit(cli::main());
}
