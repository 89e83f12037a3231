//! `osrl`: learn operational space control by reinforcement learning.
//!
//! One subcommand per file in `cmd/`. Every command that takes `--json` prints exactly one JSON
//! object on its last stdout line; errors go to stderr as one line and exit non-zero.

mod cmd;
mod config;
#[cfg(test)]
mod fuzz;
mod progress;
mod robot_entry;
mod train_json;
mod util;

/// The fuzz run's allocator: it bounds what one case may allocate (`fuzz/guard.rs`).
#[cfg(test)]
#[global_allocator]
static ALLOC: fuzz::Bounded = fuzz::Bounded;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "osrl",
    version,
    about = "Reinforcement learning for operational space control"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// LWPR regression: `osrl lwpr fit --train A.csv --test B.csv --inputs K`.
    Lwpr(cmd::lwpr::Args),
    /// Print a robot model (built-in name or URDF file), e.g. as URDF.
    Robot(cmd::robot::Args),
    /// Kinematics and dynamics of a robot at one state.
    Dynamics(cmd::dynamics::Args),
    /// Fig. 1 experiment: adaptive vs fixed reward transformation of RWR on a 1-D toy problem.
    Toy(cmd::toy::Args),
    /// Operational space control on the simulated robot along a task-space trajectory —
    /// analytical (eq. 4 / eq. 7) or a learned controller — tracking metrics, CSV and path plot.
    Simulate(cmd::simulate::Args),
    /// Train the learned operational space controller (babbling, then on-policy RWR) and save it.
    Train(cmd::train::Args),
    /// Keep learning with a saved controller on a changed robot (payload, masses, friction).
    Adapt(cmd::adapt::Args),
    /// Evaluate a saved learned controller against the analytical optimum u* (eq. 7).
    Eval(cmd::eval::Args),
    /// Run the experiments and write the report folder (index.html, results.json, figures).
    Reproduce(cmd::reproduce::Args),
    /// Draw the page of a finished `osrl reproduce` run again, from its folder's data.
    Report(cmd::report::Args),
    /// Benchmarks: `osrl bench lwpr --json` (LWPR accuracy and µs per update/predict).
    Bench(cmd::bench::Args),
}

/// A reader that closes the pipe early (`osrl eval ... --json | head -c 100`) ends the process
/// as it ends `cat`: Rust ignores SIGPIPE by default, and every `println!` would then panic.
fn default_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called first in `main`, before any thread exists; SIG_DFL is a valid handler.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn main() {
    default_sigpipe();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Lwpr(a) => cmd::lwpr::run(a),
        Command::Robot(a) => cmd::robot::run(a),
        Command::Dynamics(a) => cmd::dynamics::run(a),
        Command::Toy(a) => cmd::toy::run(a),
        Command::Simulate(a) => cmd::simulate::run(a),
        Command::Train(a) => cmd::train::run(a),
        Command::Adapt(a) => cmd::adapt::run(a),
        Command::Eval(a) => cmd::eval::run(a),
        Command::Reproduce(a) => cmd::reproduce::run(a),
        Command::Report(a) => cmd::report::run(a),
        Command::Bench(a) => cmd::bench::run(a),
    };
    if let Err(e) = result {
        // One line: the whole cause chain.
        eprintln!("error: {}", format!("{e:#}").replace('\n', " "));
        std::process::exit(1);
    }
}
