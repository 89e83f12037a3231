//! Prints the URDF of a generated arm, for the Pinocchio fixtures of the cross-checks:
//! `cargo run --release -p osrl-dynamics --example export_urdf -- mixed N SEED` writes
//! `to_urdf(random_mixed_arm(N, SEED, true))` (revolute and prismatic joints, with friction).

use osrl_dynamics::{robots, urdf::to_urdf};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args
        .iter()
        .map(String::as_str)
        .collect::<Vec<_>>()
        .as_slice()
    {
        ["mixed", n, seed] => {
            let model = robots::random_mixed_arm(
                n.parse().expect("N is a number of joints"),
                seed.parse().expect("SEED is a number"),
                true,
            );
            print!("{}", to_urdf(&model));
        }
        _ => {
            eprintln!("usage: export_urdf mixed N SEED");
            std::process::exit(2);
        }
    }
}
