//! The numbers behind a chart's lines: round-number ticks of an axis and the contour lines of
//! a grid (marching squares). Pure functions, checked without drawing.

use std::collections::HashMap;

use super::Grid;

/// Round-number ticks for `[lo, hi]`, about `target` of them, labelled with just enough decimals
/// (and a true minus sign).
pub fn nice_ticks(lo: f64, hi: f64, target: usize) -> Vec<(f64, String)> {
    if !(lo.is_finite() && hi.is_finite() && hi > lo) {
        return Vec::new();
    }
    // The round step (1, 2, 2.5 or 5 times a power of ten) whose tick count is closest to
    // `target`; ties go to the larger step.
    let count = |step: f64| ((hi / step + 1e-9).floor() - (lo / step - 1e-9).ceil() + 1.0).max(0.0);
    let mag = 10f64.powf(((hi - lo) / target.max(1) as f64).log10().floor());
    let (mult, step) = [0.5, 1.0, 2.0, 2.5, 5.0, 10.0, 20.0]
        .into_iter()
        .map(|m| (m, m * mag))
        .min_by(|a, b| {
            let da = (count(a.1) - target as f64).abs();
            let db = (count(b.1) - target as f64).abs();
            da.total_cmp(&db).then(b.1.total_cmp(&a.1))
        })
        .unwrap_or((1.0, mag));
    let decimals =
        (-(step * (1.0 + 1e-9)).log10().floor()).max(0.0) as usize + usize::from(mult == 2.5);
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            let v = if v.abs() < 1e-12 * step { 0.0 } else { v };
            (v, format!("{v:.decimals$}").replace('-', "−"))
        })
        .collect()
}

/// Contour lines of `grid` at `level` (marching squares, linear interpolation along cell edges),
/// joined into polylines. Cells with a NaN corner are skipped. A node exactly at `level` counts as
/// above it.
pub fn contour_lines(grid: &Grid, level: f64) -> Vec<Vec<(f64, f64)>> {
    let (nx, ny) = (grid.xs.len(), grid.ys.len());
    if nx < 2 || ny < 2 || grid.values.len() != nx * ny {
        return Vec::new();
    }
    // Edge ids: 2·(i·ny + j) for the edge (i, j)–(i+1, j), 2·(i·ny + j) + 1 for (i, j)–(i, j+1).
    let h_edge = |i: usize, j: usize| 2 * (i * ny + j);
    let v_edge = |i: usize, j: usize| 2 * (i * ny + j) + 1;
    let mut point: HashMap<usize, (f64, f64)> = HashMap::new();
    let mut segs: Vec<(usize, usize)> = Vec::new();
    let cross = |a: f64, b: f64| (a >= level) != (b >= level);
    let frac = |a: f64, b: f64| (level - a) / (b - a);
    for i in 0..nx - 1 {
        for j in 0..ny - 1 {
            let v00 = grid.value(i, j);
            let v10 = grid.value(i + 1, j);
            let v01 = grid.value(i, j + 1);
            let v11 = grid.value(i + 1, j + 1);
            if [v00, v10, v01, v11].iter().any(|v| v.is_nan()) {
                continue;
            }
            let (x0, x1, y0, y1) = (grid.xs[i], grid.xs[i + 1], grid.ys[j], grid.ys[j + 1]);
            // Crossed edges in the order bottom, right, top, left.
            let mut hits: Vec<usize> = Vec::with_capacity(4);
            if cross(v00, v10) {
                let id = h_edge(i, j);
                point.insert(id, (x0 + frac(v00, v10) * (x1 - x0), y0));
                hits.push(id);
            }
            if cross(v10, v11) {
                let id = v_edge(i + 1, j);
                point.insert(id, (x1, y0 + frac(v10, v11) * (y1 - y0)));
                hits.push(id);
            }
            if cross(v01, v11) {
                let id = h_edge(i, j + 1);
                point.insert(id, (x0 + frac(v01, v11) * (x1 - x0), y1));
                hits.push(id);
            }
            if cross(v00, v01) {
                let id = v_edge(i, j);
                point.insert(id, (x0, y0 + frac(v00, v01) * (y1 - y0)));
                hits.push(id);
            }
            match hits.len() {
                2 => segs.push((hits[0], hits[1])),
                4 => {
                    // Saddle: the centre value decides which corners are connected.
                    let centre = 0.25 * (v00 + v10 + v01 + v11);
                    if (centre >= level) == (v00 >= level) {
                        // v00's side joins the centre: cut off the corners v10 and v01.
                        segs.push((hits[0], hits[1]));
                        segs.push((hits[2], hits[3]));
                    } else {
                        segs.push((hits[0], hits[3]));
                        segs.push((hits[1], hits[2]));
                    }
                }
                _ => {}
            }
        }
    }
    let mut at_edge: HashMap<usize, Vec<usize>> = HashMap::new();
    for (k, &(a, b)) in segs.iter().enumerate() {
        at_edge.entry(a).or_default().push(k);
        at_edge.entry(b).or_default().push(k);
    }
    let mut used = vec![false; segs.len()];
    let mut lines = Vec::new();
    for start in 0..segs.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let (a, b) = segs[start];
        let mut chain = std::collections::VecDeque::from([a, b]);
        for forward in [true, false] {
            let mut end = if forward { b } else { a };
            loop {
                let next = at_edge
                    .get(&end)
                    .and_then(|ks| ks.iter().copied().find(|&k| !used[k]));
                let Some(k) = next else { break };
                used[k] = true;
                let (p, q) = segs[k];
                end = if p == end { q } else { p };
                if forward {
                    chain.push_back(end);
                } else {
                    chain.push_front(end);
                }
            }
        }
        lines.push(
            chain
                .iter()
                .filter_map(|id| point.get(id).copied())
                .collect(),
        );
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_ticks_are_round_and_inside() {
        let t = nice_ticks(0.1, 3.5, 6);
        let v: Vec<f64> = t.iter().map(|t| t.0).collect();
        assert_eq!(v, vec![0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5]);
        assert_eq!(t[0].1, "0.5");
        let t = nice_ticks(-1.0, 1.0, 5);
        assert_eq!(t.first().map(|t| t.1.as_str()), Some("−1.0"));
        assert!(t.iter().any(|t| t.1 == "0.0"));
    }

    #[test]
    fn contours_of_a_plane_are_straight_lines_at_the_level() {
        // f = x + 2y on a 11 x 7 grid: the level set x + 2y = 1.3 is one straight line.
        let xs: Vec<f64> = (0..11).map(|i| i as f64 * 0.1).collect();
        let ys: Vec<f64> = (0..7).map(|j| j as f64 * 0.1).collect();
        let values = xs
            .iter()
            .flat_map(|x| ys.iter().map(move |y| x + 2.0 * y))
            .collect();
        let g = Grid { xs, ys, values };
        let lines = contour_lines(&g, 1.3);
        assert_eq!(lines.len(), 1, "{lines:?}");
        assert!(lines[0].len() > 5);
        for &(x, y) in &lines[0] {
            assert!((x + 2.0 * y - 1.3).abs() < 1e-12, "({x}, {y})");
        }
        // Endpoints on the grid's boundary.
        let on_edge = |(x, y): (f64, f64)| {
            x.abs() < 1e-12 || (x - 1.0).abs() < 1e-12 || y.abs() < 1e-12 || (y - 0.6).abs() < 1e-12
        };
        assert!(on_edge(lines[0][0]) && on_edge(*lines[0].last().unwrap()));
        assert!(contour_lines(&g, 5.0).is_empty());
    }

    #[test]
    fn a_closed_contour_closes() {
        // f = x² + y² on [−1, 1]²: the level 0.25 is a closed ring.
        let xs: Vec<f64> = (0..21).map(|i| -1.0 + 0.1 * i as f64).collect();
        let ys = xs.clone();
        let values = xs
            .iter()
            .flat_map(|x| ys.iter().map(move |y| x * x + y * y))
            .collect();
        let lines = contour_lines(&Grid { xs, ys, values }, 0.25);
        assert_eq!(lines.len(), 1);
        let l = &lines[0];
        assert_eq!(l.first(), l.last(), "ring is closed");
        for &(x, y) in l {
            assert!(((x * x + y * y).sqrt() - 0.5).abs() < 0.02);
        }
    }
}
