//! Save/load round trips bit-exactly; bad files and bad inputs are errors that change nothing.

mod common;

use lwpr::{Lwpr, LwprError};
use rand::SeedableRng;

fn trained() -> Lwpr {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let d = common::cross_train(&mut rng, 300);
    let mut m = Lwpr::new(2, 1, &common::cross_config()).unwrap();
    for _ in 0..5 {
        for (x, &y) in d.x.iter().zip(&d.y) {
            m.update(x, &[y]).unwrap();
        }
    }
    m
}

#[test]
fn save_load_round_trips_bit_exactly() {
    let mut a = trained();
    let path = std::env::temp_dir().join(format!("lwpr-io-{}.bin", std::process::id()));
    a.save(&path).unwrap();
    let mut b = Lwpr::load(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(a.to_bytes(), b.to_bytes());
    let grid = common::cross_grid();
    let (mut ya, mut yb, mut ca, mut cb) = ([0.0], [0.0], [0.0], [0.0]);
    for x in grid.x.iter().step_by(7) {
        a.predict_conf(x, &mut ya, &mut ca).unwrap();
        b.predict_conf(x, &mut yb, &mut cb).unwrap();
        assert_eq!(ya[0].to_bits(), yb[0].to_bits());
        assert_eq!(ca[0].to_bits(), cb[0].to_bits());
    }
    // Learning continues identically.
    for x in grid.x.iter().step_by(3) {
        let t = [common::cross(x[0], x[1])];
        assert_eq!(a.update(x, &t).unwrap(), b.update(x, &t).unwrap());
    }
    assert_eq!(a.to_bytes(), b.to_bytes());
}

#[test]
fn truncated_or_corrupted_bytes_are_errors() {
    let a = trained();
    let bytes = a.to_bytes();
    for cut in [0, 5, 19, 20, bytes.len() / 2, bytes.len() - 1] {
        assert!(matches!(
            Lwpr::from_bytes(&bytes[..cut]),
            Err(LwprError::Format(_))
        ));
    }
    for pos in [3, 9, 15, 40, bytes.len() / 2, bytes.len() - 3] {
        let mut bad = bytes.clone();
        bad[pos] ^= 0x10;
        assert!(
            Lwpr::from_bytes(&bad).is_err(),
            "flipped byte {pos} accepted"
        );
    }
    let mut longer = bytes.clone();
    longer.push(0);
    assert!(Lwpr::from_bytes(&longer).is_err());
    assert!(Lwpr::load("/nonexistent/lwpr.bin").is_err());
}

#[test]
fn bad_inputs_are_errors_and_change_nothing() {
    let mut m = trained();
    let before = m.to_bytes();
    let mut y = [0.0];
    let nan = f64::NAN;
    assert!(matches!(
        m.update(&[0.1, nan], &[0.0]),
        Err(LwprError::NonFinite { .. })
    ));
    assert!(m.update(&[0.1, 0.2], &[f64::INFINITY]).is_err());
    assert!(matches!(
        m.update(&[0.1], &[0.0]),
        Err(LwprError::Dimension { .. })
    ));
    assert!(m.update(&[0.1, 0.2], &[0.0, 1.0]).is_err());
    assert!(m.predict(&[nan, 0.0], &mut y).is_err());
    assert!(m.predict(&[0.0, 0.0, 0.0], &mut y).is_err());
    assert!(m.predict(&[0.0, 0.0], &mut [0.0, 0.0]).is_err());
    assert!(m
        .predict_jacobian(&[0.0, 0.0], &mut y, &mut [0.0; 3])
        .is_err());
    assert_eq!(before, m.to_bytes());
    assert_eq!(m.drain_events().count(), m.n_rfs_total());
}

#[test]
fn no_support_is_reported() {
    let mut m = trained();
    let mut y = [123.0];
    let r = m.predict(&[30.0, 30.0], &mut y);
    assert!(matches!(r, Err(LwprError::NoActiveRf { output: 0 })));
    assert_eq!(y[0], 123.0, "output untouched");
    let s = m.predict(&[0.0, 0.0], &mut y).unwrap();
    assert!(s.sum_w > 0.5);
}

/// A failed save (the path is a folder) is an I/O error that leaves no temporary file and
/// changes neither the model nor an existing file; a save over an existing file replaces it.
#[test]
fn failed_save_leaves_no_temporary_file() {
    let dir = std::env::temp_dir().join(format!("lwpr-io-save-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("folder")).unwrap();
    let listing = || {
        let mut v: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    };
    let a = trained();
    let before = a.to_bytes();
    let err = a.save(dir.join("folder")).unwrap_err();
    assert!(matches!(err, LwprError::File(_)), "{err}");
    assert!(err.to_string().contains("is a directory"), "{err}");
    // The message once: it is not repeated by a `source`.
    assert!(std::error::Error::source(&err).is_none());
    assert_eq!(listing(), ["folder"]);
    assert_eq!(a.to_bytes(), before);
    // Replacing an existing file.
    let file = dir.join("m.bin");
    std::fs::write(&file, b"old").unwrap();
    a.save(&file).unwrap();
    assert_eq!(std::fs::read(&file).unwrap(), before);
    assert_eq!(listing(), ["folder", "m.bin"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A file or symbolic link already at a temporary file's name is never written through: the
/// save takes another name, and the linked file is unchanged.
#[cfg(unix)]
#[test]
fn save_does_not_write_through_an_existing_temporary_name() {
    let dir = std::env::temp_dir().join(format!("lwpr-io-link-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let outside = dir.join("outside.txt");
    std::fs::write(&outside, b"keep").unwrap();
    let target = dir.join("m.bin");
    // The first names the counter gives (other tests in this process may have used some).
    for n in 0..20 {
        let name = format!("m.bin.{}.{n}.tmp", std::process::id());
        std::os::unix::fs::symlink(&outside, dir.join(name)).unwrap();
    }
    let a = trained();
    a.save(&target).unwrap();
    assert_eq!(std::fs::read(&outside).unwrap(), b"keep");
    assert_eq!(std::fs::read(&target).unwrap(), a.to_bytes());
    std::fs::remove_dir_all(&dir).unwrap();
}
