//! The standard cross test (`docs/lwpr.md`, "The cross tests"), small version: seeds 0–3 of the full 500-point,
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
/// rotated, `Rᵀ x` gives them back, `R` orthogonal. The same for the test grid, and in 25
/// dimensions (the reference library's Matlab test) with the same 2-D points; fewer than 2
/// dimensions are refused.
#[test]
fn cross_21d_embeddings_share_the_points() {
    use nalgebra::{DMatrix, DVector};
    use rand::SeedableRng;
    let seed = 3;
    let plain = common::cross_train(&mut rand_chacha::ChaCha8Rng::seed_from_u64(seed), 500);
    let grid = common::cross_grid();
    for d in [21, 25] {
        let (id_train, id_test, id) = common::cross_nd_data(seed, d, common::Embedding::Identity);
        let (rot_train, rot_test, r) = common::cross_nd_data(seed, d, common::Embedding::Rotation);
        assert_eq!(id, DMatrix::identity(d, d));
        let eye = r.transpose() * &r;
        assert!((eye - DMatrix::identity(d, d)).amax() < 1e-12);
        for (two, id_d, rot_d) in [
            (&plain, &id_train, &rot_train),
            (&grid, &id_test, &rot_test),
        ] {
            assert_eq!(two.x.len(), id_d.x.len());
            assert_eq!((&two.y, &two.y), (&id_d.y, &rot_d.y));
            for ((p, u), v) in two.x.iter().zip(&id_d.x).zip(&rot_d.x) {
                assert_eq!((u.len(), v.len()), (d, d));
                assert_eq!(&u[..2], &p[..]);
                assert!(u[2..].iter().all(|&z| z == 0.0));
                let back = r.transpose() * DVector::from_column_slice(v);
                assert!((back[0] - p[0]).abs() < 1e-12 && (back[1] - p[1]).abs() < 1e-12);
                assert!(back.rows(2, d - 2).amax() < 1e-12);
            }
        }
    }
    // `cross21_data` is the 21-D case.
    let (a, _, ra) = common::cross21_data(seed, common::Embedding::Rotation);
    let (b, _, rb) = common::cross_nd_data(seed, 21, common::Embedding::Rotation);
    assert_eq!((a.x, ra), (b.x, rb.clone()));
    // The rotation differs between seeds.
    let (_, _, r4) = common::cross21_data(4, common::Embedding::Rotation);
    assert!((r4 - rb).amax() > 0.1);
    let cfg = common::cross21_config();
    let err = common::cross_nd_run(&cfg, 0, 1, 1, common::Embedding::Rotation).unwrap_err();
    assert!(err.to_string().contains("at least 2 dimensions"), "{err}");
}
