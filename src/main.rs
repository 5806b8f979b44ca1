//! The `touchdown` program: the command line of `touchdown::commands`.
fn main() -> std::process::ExitCode {
    touchdown::commands::main()
}
