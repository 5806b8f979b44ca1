fn main() -> std::process::ExitCode {
    touchdown::commands::main()
}
