//! Contour lines by marching squares, and the viridis colour map.

use super::Rgb;

type Pt = (f64, f64);

/// Line segments where `z` (values `z[iy][ix]` on the grid `xs × ys`) crosses `level`, by
/// marching squares with linear interpolation along cell edges; saddle cells are split by the
/// cell-centre average. Cells with a non-finite corner are skipped. Returns no segments if the
/// grid's shape does not match `xs`/`ys`.
pub fn contour_segments(xs: &[f64], ys: &[f64], z: &[Vec<f64>], level: f64) -> Vec<[Pt; 2]> {
    let mut out = Vec::new();
    if z.len() != ys.len() || z.iter().any(|row| row.len() != xs.len()) {
        return out;
    }
    let cross = |(xa, ya, za): (f64, f64, f64), (xb, yb, zb): (f64, f64, f64)| {
        let t = (level - za) / (zb - za);
        (xa + t * (xb - xa), ya + t * (yb - ya))
    };
    for iy in 0..ys.len().saturating_sub(1) {
        for ix in 0..xs.len().saturating_sub(1) {
            let c00 = (xs[ix], ys[iy], z[iy][ix]);
            let c10 = (xs[ix + 1], ys[iy], z[iy][ix + 1]);
            let c11 = (xs[ix + 1], ys[iy + 1], z[iy + 1][ix + 1]);
            let c01 = (xs[ix], ys[iy + 1], z[iy + 1][ix]);
            if ![c00.2, c10.2, c11.2, c01.2].iter().all(|v| v.is_finite()) {
                continue;
            }
            let above = |c: (f64, f64, f64)| c.2 >= level;
            // Edges in order: bottom, right, top, left.
            let edges = [(c00, c10), (c10, c11), (c01, c11), (c00, c01)];
            let hits: Vec<Option<Pt>> = edges
                .iter()
                .map(|&(a, b)| (above(a) != above(b)).then(|| cross(a, b)))
                .collect();
            let pts: Vec<Pt> = hits.iter().flatten().copied().collect();
            match pts.len() {
                2 => out.push([pts[0], pts[1]]),
                4 => {
                    let centre = (c00.2 + c10.2 + c11.2 + c01.2) / 4.0;
                    let [b, r, t, l] = [pts[0], pts[1], pts[2], pts[3]];
                    if (centre >= level) == above(c00) {
                        out.push([b, r]);
                        out.push([t, l]);
                    } else {
                        out.push([b, l]);
                        out.push([r, t]);
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// [`contour_segments`] joined into polylines (segments sharing an end point are chained; closed
/// contours end where they start). Fewer, longer lines draw dashes properly.
pub fn contour_lines(xs: &[f64], ys: &[f64], z: &[Vec<f64>], level: f64) -> Vec<Vec<Pt>> {
    use std::collections::HashMap;
    let segs = contour_segments(xs, ys, z, level);
    let key = |p: Pt| (p.0.to_bits(), p.1.to_bits());
    let mut at: HashMap<(u64, u64), Vec<usize>> = HashMap::new();
    for (i, s) in segs.iter().enumerate() {
        at.entry(key(s[0])).or_default().push(i);
        at.entry(key(s[1])).or_default().push(i);
    }
    let mut used = vec![false; segs.len()];
    let mut lines = Vec::new();
    for start in 0..segs.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut line = std::collections::VecDeque::from(vec![segs[start][0], segs[start][1]]);
        // Grow at the back, then at the front.
        for front in [false, true] {
            loop {
                let end = if front { line[0] } else { line[line.len() - 1] };
                let next = at[&key(end)].iter().copied().find(|&j| !used[j]);
                let Some(j) = next else { break };
                used[j] = true;
                let p = if key(segs[j][0]) == key(end) {
                    segs[j][1]
                } else {
                    segs[j][0]
                };
                if front {
                    line.push_front(p);
                } else {
                    line.push_back(p);
                }
            }
        }
        lines.push(line.into_iter().collect());
    }
    lines
}

/// The viridis colour map at `t` in [0, 1] (clamped; NaN gives the low end).
pub fn viridis(t: f64) -> Rgb {
    const STOPS: [(u8, u8, u8); 9] = [
        (68, 1, 84),
        (71, 44, 122),
        (59, 81, 139),
        (44, 113, 142),
        (33, 144, 141),
        (39, 173, 129),
        (92, 200, 99),
        (170, 220, 50),
        (253, 231, 37),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (STOPS.len() - 1) as f64;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f64;
    let mix = |a: u8, b: u8| (a as f64 + f * (b as f64 - a as f64)).round() as u8;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    Rgb(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_contour_lies_on_the_circle() {
        let g: Vec<f64> = (0..41).map(|i| -2.0 + 0.1 * i as f64).collect();
        let z: Vec<Vec<f64>> = g
            .iter()
            .map(|y| g.iter().map(|x| x * x + y * y).collect())
            .collect();
        let segs = contour_segments(&g, &g, &z, 1.0);
        assert!(segs.len() > 30);
        for [a, b] in segs {
            for (x, y) in [a, b] {
                assert!(((x * x + y * y).sqrt() - 1.0).abs() < 0.02, "({x}, {y})");
            }
        }
        assert!(contour_segments(&g, &g, &z, 100.0).is_empty());
        let lines = contour_lines(&g, &g, &z, 1.0);
        assert_eq!(lines.len(), 1, "one closed circle");
        assert_eq!(lines[0].first(), lines[0].last());
        assert!(contour_segments(&g[..3], &g, &z, 1.0).is_empty());
    }

    #[test]
    fn viridis_ends_and_clamps() {
        assert_eq!(viridis(0.0), Rgb(68, 1, 84));
        assert_eq!(viridis(1.0), Rgb(253, 231, 37));
        assert_eq!(viridis(7.0), viridis(1.0));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
    }
}
