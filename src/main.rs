fn main() -> std::process::ExitCode {
    touchdown::cli::main()
}
