//! The standard cross test (`shared/LWPR.md`), small version: seeds 0–3 of the full 500-point,
//! 20-epoch protocol. This is a regression guard (every seed below 0.06, at most 45 RFs); the
//! target itself (median over 10 seeds ≤ 0.04) is measured by `osrl bench lwpr`.

mod common;

#[test]
fn cross_2d_learns() {
    for seed in 0..4 {
        let r = common::cross_run(&common::cross_config(), seed, 20).unwrap();
        assert!(r.nmse < 0.06, "seed {seed}: nMSE {}", r.nmse);
        assert!(r.n_rfs <= 45, "seed {seed}: {} RFs", r.n_rfs);
    }
}

/// The 21-D test's two embeddings of a seed carry the same points: unrotated, the 2-D points
/// (the same draws as `cross_train` with that seed) in inputs 0 and 1 and zeros elsewhere;
/// rotated, `Rᵀ x` gives them back, `R` orthogonal. The same for the test grid.
#[test]
fn cross_21d_embeddings_share_the_points() {
    use nalgebra::DVector;
    use rand::SeedableRng;
    let seed = 3;
    let plain = common::cross_train(&mut rand_chacha::ChaCha8Rng::seed_from_u64(seed), 500);
    let grid = common::cross_grid();
    let (id_train, id_test, id) = common::cross21_data(seed, common::Embedding::Identity);
    let (rot_train, rot_test, r) = common::cross21_data(seed, common::Embedding::Rotation);
    assert_eq!(id, nalgebra::DMatrix::identity(21, 21));
    let eye = r.transpose() * &r;
    assert!((eye - nalgebra::DMatrix::identity(21, 21)).amax() < 1e-12);
    for (two, id_d, rot_d) in [
        (&plain, &id_train, &rot_train),
        (&grid, &id_test, &rot_test),
    ] {
        assert_eq!(two.x.len(), id_d.x.len());
        assert_eq!((&two.y, &two.y), (&id_d.y, &rot_d.y));
        for ((p, u), v) in two.x.iter().zip(&id_d.x).zip(&rot_d.x) {
            assert_eq!((u.len(), v.len()), (21, 21));
            assert_eq!(&u[..2], &p[..]);
            assert!(u[2..].iter().all(|&z| z == 0.0));
            let back = r.transpose() * DVector::from_column_slice(v);
            assert!((back[0] - p[0]).abs() < 1e-12 && (back[1] - p[1]).abs() < 1e-12);
            assert!(back.rows(2, 19).amax() < 1e-12);
        }
    }
    // The rotation differs between seeds.
    let (_, _, r4) = common::cross21_data(4, common::Embedding::Rotation);
    assert!((r4 - r).amax() > 0.1);
}
