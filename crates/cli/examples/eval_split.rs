//! The error split of saved models on their own (base) figure-8 (`docs/family.md`): tracking,
//! command nMSE, its null-space part, the nominal behaviour's error, the error of `Â` and the
//! floor of the learner's own `Â` and `û0`.
//!
//! ```sh
//! cargo run --release -p osrl-cli --example eval_split -- A.osrl B.osrl …
//! ```

use anyhow::Result;
use osrl_experiments::Setup;
use osrl_learn::SavedModel;

fn main() -> Result<()> {
    for file in std::env::args().skip(1) {
        let saved = SavedModel::load(std::path::Path::new(&file))?;
        let setup = Setup::from_saved(&saved)?;
        let (_, mut learner, model) = saved.into_parts();
        let e = setup.evaluator(&model)?.evaluate(&mut learner)?;
        println!(
            "{file}: {:.3} mm, nMSE {:.4} (null {:.4}, floor null {:.4}), nominal nMSE {:.4} \
             (null {:.4}), gain error {:.4}",
            e.tracking_rms_mm,
            e.command_nmse,
            e.command_nmse_null,
            e.floor_nmse_null,
            e.nominal_nmse,
            e.nominal_nmse_null,
            e.gain_error
        );
    }
    Ok(())
}
