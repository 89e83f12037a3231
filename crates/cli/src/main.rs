//! `osrl`: learn operational space control by reinforcement learning.
//!
//! One subcommand per file in `cmd/`. Every command that takes `--json` prints exactly one JSON
//! object on its last stdout line; errors go to stderr as one line and exit non-zero.

mod cmd;
mod util;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(name = "osrl", version, about = "Reinforcement learning for operational space control")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print a robot model (built-in name or URDF file), e.g. as URDF.
    Robot(cmd::robot::Args),
    /// Kinematics and dynamics of a robot at one state.
    Dynamics(cmd::dynamics::Args),
}

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Robot(a) => cmd::robot::run(a),
        Command::Dynamics(a) => cmd::dynamics::run(a),
    };
    if let Err(e) = result {
        // One line: the whole cause chain.
        eprintln!("error: {}", format!("{e:#}").replace('\n', " "));
        std::process::exit(1);
    }
}
