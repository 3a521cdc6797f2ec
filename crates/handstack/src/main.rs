//! `handstack`: run a tactile hand stack from a scene file on its real devices; the command line
//! is [`handstack::cli`], its hardware Linux's device files.

fn main() -> std::process::ExitCode {
    handstack::cli::main(&|| Box::new(handstack::stack::platform::LinuxPlatform::new()))
}
