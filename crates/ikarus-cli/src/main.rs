//! `ikarus`: inverse kinematics for planar arms, from the command line (see [`ikarus_cli::main`]).

fn main() -> std::process::ExitCode {
    ikarus_cli::main()
}
