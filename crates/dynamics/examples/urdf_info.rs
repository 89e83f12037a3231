//! What the URDF loader makes of a file: `cargo run --release -p osrl-dynamics --example urdf_info
//! -- FILE [--tip LINK] [--lock JOINT[=VALUE]]... [--unlock JOINT]...` prints the degrees of
//! freedom, the tip and the rule that chose it, and the locked joints (or the loader's error).

use osrl_dynamics::urdf::{load_urdf_with, UrdfOptions};

fn main() {
    let mut args = std::env::args().skip(1);
    let mut opts = UrdfOptions::default();
    let mut files = Vec::new();
    while let Some(a) = args.next() {
        let mut value = || args.next().expect("a value after the flag");
        match a.as_str() {
            "--tip" => opts.tip = Some(value()),
            "--lock" => opts.push_lock(&value()).expect("a lock spec"),
            "--unlock" => opts.unlock.push(value()),
            _ => files.push(a),
        }
    }
    for f in files {
        match load_urdf_with(std::path::Path::new(&f), &opts) {
            Ok(model) => {
                let spec = model.spec();
                let import = spec.urdf.as_ref().expect("a URDF model");
                let joints: Vec<String> = spec
                    .links
                    .iter()
                    .map(|l| format!("{}({:?})", l.joint_name, l.kind))
                    .collect();
                println!("{f}: {} DOF [{}]", model.nq(), joints.join(", "));
                println!(
                    "  tip '{}' ({}), ee_offset {:?}",
                    import.tip,
                    import.tip_rule,
                    spec.ee_offset.as_slice()
                );
                for l in &import.locked {
                    println!("  locked '{}' = {} ({})", l.name, l.value, l.reason);
                }
            }
            Err(e) => println!("{f}: ERROR {e}"),
        }
    }
}
