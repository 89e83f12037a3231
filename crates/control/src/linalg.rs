//! Small allocation-free dense linear algebra on preallocated buffers: an in-place Cholesky
//! factorisation and its solves (the controllers' hot path must not allocate).

use nalgebra::DMatrix;

/// Factorises the symmetric matrix `a = L Lᵀ` in place: on success the lower triangle holds `L`
/// (the strict upper triangle is left as it was). Reads only the lower triangle.
///
/// Fails with the index of the first pivot that is not positive — relative to the matrix's largest
/// diagonal entry, `d ≤ 1e-14·max_i a_ii` — or not finite; `a` is then partly overwritten.
pub(crate) fn cholesky_in_place(a: &mut DMatrix<f64>) -> Result<(), usize> {
    let n = a.nrows();
    let mut scale = 0.0f64;
    for i in 0..n {
        scale = scale.max(a[(i, i)].abs());
    }
    let tol = 1e-14 * scale;
    for j in 0..n {
        let mut d = a[(j, j)];
        for k in 0..j {
            d -= a[(j, k)] * a[(j, k)];
        }
        if !d.is_finite() || d <= tol {
            return Err(j);
        }
        let d = d.sqrt();
        a[(j, j)] = d;
        for i in j + 1..n {
            let mut s = a[(i, j)];
            for k in 0..j {
                s -= a[(i, k)] * a[(j, k)];
            }
            a[(i, j)] = s / d;
        }
    }
    Ok(())
}

/// Solves `L Lᵀ x = b` in place (`b` becomes `x`), with `L` from [`cholesky_in_place`].
pub(crate) fn cholesky_solve(l: &DMatrix<f64>, b: &mut [f64]) {
    let n = l.nrows();
    // L y = b
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[(i, k)] * b[k];
        }
        b[i] = s / l[(i, i)];
    }
    // Lᵀ x = y
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[(k, i)] * b[k];
        }
        b[i] = s / l[(i, i)];
    }
}

/// Solves `L Lᵀ X = B` in place for every column of `b`.
pub(crate) fn cholesky_solve_columns(l: &DMatrix<f64>, b: &mut DMatrix<f64>, cols: usize) {
    for c in 0..cols {
        cholesky_solve(l, b.column_mut(c).as_mut_slice());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_matches_nalgebra_and_solves() {
        let a = DMatrix::from_row_slice(3, 3, &[4.0, 2.0, 0.6, 2.0, 5.0, 1.0, 0.6, 1.0, 3.0]);
        let mut l = a.clone();
        cholesky_in_place(&mut l).unwrap();
        let reference = a.clone().cholesky().unwrap().l();
        for i in 0..3 {
            for j in 0..=i {
                assert!((l[(i, j)] - reference[(i, j)]).abs() < 1e-14);
            }
        }
        let mut x = [1.0, -2.0, 0.5];
        cholesky_solve(&l, &mut x);
        let back = &a * nalgebra::DVector::from_row_slice(&x);
        assert!((back - nalgebra::DVector::from_row_slice(&[1.0, -2.0, 0.5])).amax() < 1e-13);
    }

    #[test]
    fn cholesky_rejects_indefinite_and_nan() {
        let mut a = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 1.0]);
        assert_eq!(cholesky_in_place(&mut a), Err(1));
        let mut b = DMatrix::from_row_slice(2, 2, &[f64::NAN, 0.0, 0.0, 1.0]);
        assert_eq!(cholesky_in_place(&mut b), Err(0));
        let mut z = DMatrix::<f64>::zeros(2, 2);
        assert_eq!(cholesky_in_place(&mut z), Err(0));
    }
}
