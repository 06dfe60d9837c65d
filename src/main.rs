fn main() {
    std::process::exit(specgen::cli::main());
}
