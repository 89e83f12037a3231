//! The time series of the runs as CSV, one row per control step, and back: `simulate.csv` of an
//! analytical run (`t, <axis>_d…, <axis>…, error_mm, q…, u…`) and the learned controller's
//! evaluation (the same columns, then `u_star…`). Numbers are written exactly (see
//! [`crate::csv::write`]), so a series read back is the one written.

use crate::csv::{self, Table};
use crate::error::{ReportError, Result};
use crate::figures::path::AXES;
use osrl_learn::eval::EvalSeries;
use std::path::Path;

/// The header: `t`, the desired and actual task coordinates, `error_mm`, `q0…`, `u0…`, and
/// `u_star0…` when `u_star`.
fn header(axes: &[usize], n: usize, u_star: bool) -> Vec<String> {
    let mut head = vec!["t".to_string()];
    head.extend(axes.iter().map(|&a| format!("{}_d", AXES[a])));
    head.extend(axes.iter().map(|&a| AXES[a].to_string()));
    head.push("error_mm".into());
    head.extend((0..n).map(|i| format!("q{i}")));
    head.extend((0..n).map(|i| format!("u{i}")));
    if u_star {
        head.extend((0..n).map(|i| format!("u_star{i}")));
    }
    head
}

fn error_mm(x_d: &[f64], x: &[f64]) -> f64 {
    1e3 * x_d
        .iter()
        .zip(x)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Writes an analytical run's series; `axes` are the world axes of its task coordinates.
///
/// # Errors
/// An I/O error.
pub fn write_run(path: &Path, s: &osrl_control::Series, axes: &[usize]) -> Result<()> {
    let (n, m) = (s.n, s.m);
    let rows = (0..s.len()).map(|k| {
        let (xd, x) = (&s.x_d[k * m..(k + 1) * m], &s.x[k * m..(k + 1) * m]);
        let mut row = vec![s.t[k]];
        row.extend(xd);
        row.extend(x);
        row.push(1e3 * s.error(k));
        row.extend(&s.q[k * n..(k + 1) * n]);
        row.extend(&s.u[k * n..(k + 1) * n]);
        row
    });
    csv::write(path, &header(axes, n, false), rows)
}

/// Writes a learned controller's evaluation series for a robot with `n` joints.
///
/// # Errors
/// An I/O error.
pub fn write_eval(path: &Path, es: &EvalSeries, n: usize, axes: &[usize]) -> Result<()> {
    let m = axes.len();
    let rows = (0..es.t.len()).map(|k| {
        let (xd, x) = (&es.x_d[k * m..(k + 1) * m], &es.x[k * m..(k + 1) * m]);
        let mut row = vec![es.t[k]];
        row.extend(xd);
        row.extend(x);
        row.push(error_mm(xd, x));
        row.extend(&es.q[k * n..(k + 1) * n]);
        row.extend(&es.u[k * n..(k + 1) * n]);
        row.extend(&es.u_star[k * n..(k + 1) * n]);
        row
    });
    csv::write(path, &header(axes, n, true), rows)
}

/// The columns of `table` named `prefix0, prefix1, …` (as many as there are), row-major.
fn block(table: &Table, names: &[String]) -> Result<Vec<f64>> {
    let cols: Vec<usize> = names
        .iter()
        .map(|n| {
            table.column(n).ok_or_else(|| {
                ReportError::Folder(format!("{}: no column {n}", table.path.display()))
            })
        })
        .collect::<Result<_>>()?;
    Ok(table
        .rows
        .iter()
        .flat_map(|r| cols.iter().map(move |&c| r[c]))
        .collect())
}

/// The joints (`q0…`) and task axes (`x_d`, `y_d`, `z_d` present) of a series file.
fn shape(table: &Table) -> (usize, Vec<usize>) {
    let n = (0..)
        .take_while(|i| table.column(&format!("q{i}")).is_some())
        .count();
    let axes = (0..3)
        .filter(|&a| table.column(&format!("{}_d", AXES[a])).is_some())
        .collect();
    (n, axes)
}

/// The columns of one series file: times, desired and actual task coordinates, `q`, `u`.
struct Columns {
    n: usize,
    m: usize,
    t: Vec<f64>,
    x_d: Vec<f64>,
    x: Vec<f64>,
    q: Vec<f64>,
    u: Vec<f64>,
}

fn columns(table: &Table) -> Result<Columns> {
    let (n, axes) = shape(table);
    let names = |f: &dyn Fn(usize) -> String, k: usize| (0..k).map(f).collect::<Vec<_>>();
    let ax = |suffix: &'static str| {
        axes.iter()
            .map(|&a| format!("{}{suffix}", AXES[a]))
            .collect::<Vec<_>>()
    };
    Ok(Columns {
        n,
        m: axes.len(),
        t: block(table, &["t".to_string()])?,
        x_d: block(table, &ax("_d"))?,
        x: block(table, &ax(""))?,
        q: block(table, &names(&|i| format!("q{i}"), n))?,
        u: block(table, &names(&|i| format!("u{i}"), n))?,
    })
}

/// Reads a series written by [`write_run`].
///
/// # Errors
/// A missing or malformed file, or a missing column.
pub fn read_run(path: &Path) -> Result<osrl_control::Series> {
    let c = columns(&Table::read_series(path)?)?;
    Ok(osrl_control::Series {
        n: c.n,
        m: c.m,
        t: c.t,
        x_d: c.x_d,
        x: c.x,
        q: c.q,
        u: c.u,
    })
}

/// Reads a series written by [`write_eval`] (without the command times, which it does not
/// hold).
///
/// # Errors
/// A missing or malformed file, or a missing column.
pub fn read_eval(path: &Path) -> Result<EvalSeries> {
    let table = Table::read_series(path)?;
    let c = columns(&table)?;
    let u_star = block(
        &table,
        &(0..c.n).map(|i| format!("u_star{i}")).collect::<Vec<_>>(),
    )?;
    Ok(EvalSeries {
        t: c.t,
        x_d: c.x_d,
        x: c.x,
        u: c.u,
        u_star,
        q: c.q,
        command_seconds: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_read_back_are_the_series_written() {
        let dir = std::env::temp_dir().join(format!("osrl-series-{}", std::process::id()));
        let s = osrl_control::Series {
            n: 2,
            m: 2,
            t: vec![0.0, 0.002],
            x_d: vec![0.1, 0.2, 0.1 + 1e-17, 1.0 / 3.0],
            x: vec![0.3, f64::NAN, -0.0, 5e-324],
            q: vec![1.0, 2.0, 3.0, 4.0],
            u: vec![-1.5, 2.25, 1e300, f64::INFINITY],
        };
        let p = dir.join("run.csv");
        write_run(&p, &s, &[0, 2]).unwrap();
        let back = read_run(&p).unwrap();
        assert_eq!((back.n, back.m), (2, 2));
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for (a, b) in [
            (&s.t, &back.t),
            (&s.x_d, &back.x_d),
            (&s.x, &back.x),
            (&s.q, &back.q),
            (&s.u, &back.u),
        ] {
            assert_eq!(bits(a), bits(b));
        }
        let es = EvalSeries {
            t: s.t.clone(),
            x_d: s.x_d.clone(),
            x: s.x.clone(),
            u: s.u.clone(),
            u_star: vec![0.5, 0.25, 0.125, 1.0 / 7.0],
            q: s.q.clone(),
            command_seconds: vec![1e-6, 2e-6],
        };
        let p = dir.join("eval.csv");
        write_eval(&p, &es, 2, &[0, 2]).unwrap();
        let back = read_eval(&p).unwrap();
        assert_eq!(bits(&back.u_star), bits(&es.u_star));
        assert_eq!(bits(&back.x), bits(&es.x));
        assert!(back.command_seconds.is_empty());
        std::fs::write(&p, "t,x_d\n0,1\n").unwrap();
        assert!(read_eval(&p).unwrap_err().to_string().contains("no column"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
