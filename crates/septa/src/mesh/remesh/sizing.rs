//! The target edge length where it must be below `L`: near two fixed
//! vertices closer than `L` (corners of short chains, chains meeting at a
//! small distance), triangles of size `L` would have an angle of about
//! `distance / L` there. The target grows from that distance by half the
//! distance to them (a graded mesh, as in CGAL's and DelPSC's protecting
//! balls), never below `L / 16`.

use rustc_hash::FxHashMap;

use super::soup::{add, dist, scale, Kind, Soup, V};

/// How fast the target grows away from a short feature.
const GRADING: f64 = 0.5;

pub(super) struct Sizing {
    l: f64,
    /// Short features: middle and length.
    features: Vec<(V, f64)>,
    cells: FxHashMap<[i64; 3], Vec<u32>>,
}

fn cell(p: V, size: f64) -> [i64; 3] {
    p.map(|c| (c / size).floor() as i64)
}

impl Sizing {
    /// The features of `s`'s fixed vertices for the target length `l`.
    pub fn new(s: &Soup, l: f64) -> Sizing {
        let mut grid: FxHashMap<[i64; 3], Vec<u32>> = FxHashMap::default();
        let fixed: Vec<u32> = (0..s.x.len() as u32)
            .filter(|&v| s.kind[v as usize] == Kind::Fixed && !s.vt[v as usize].is_empty())
            .collect();
        for &v in &fixed {
            grid.entry(cell(s.x[v as usize], l)).or_default().push(v);
        }
        let floor = l / 16.0;
        let mut features = Vec::new();
        for &v in &fixed {
            let c = cell(s.x[v as usize], l);
            for i in -1..=1 {
                for j in -1..=1 {
                    for k in -1..=1 {
                        for &w in grid.get(&[c[0] + i, c[1] + j, c[2] + k]).map_or(&[][..], |x| &x[..]) {
                            let d = s.len(v, w);
                            if w > v && d < l {
                                let mid = scale(add(s.x[v as usize], s.x[w as usize]), 0.5);
                                features.push((mid, d.max(floor)));
                            }
                        }
                    }
                }
            }
        }
        let mut cells: FxHashMap<[i64; 3], Vec<u32>> = FxHashMap::default();
        for (i, (m, _)) in features.iter().enumerate() {
            cells.entry(cell(*m, l)).or_default().push(i as u32);
        }
        Sizing { l, features, cells }
    }

    /// The target edge length at `p`.
    pub fn at(&self, p: V) -> f64 {
        if self.features.is_empty() {
            return self.l;
        }
        let mut h = self.l;
        let c = cell(p, self.l);
        // beyond 2 L / GRADING... a feature no longer matters: within 2 cells
        let r = (1.0 / GRADING).ceil() as i64 + 1;
        for i in -r..=r {
            for j in -r..=r {
                for k in -r..=r {
                    if let Some(list) = self.cells.get(&[c[0] + i, c[1] + j, c[2] + k]) {
                        for &f in list {
                            let (m, d) = self.features[f as usize];
                            h = h.min(d + GRADING * dist(p, m));
                        }
                    }
                }
            }
        }
        h
    }

    /// The target length of the edge `ab` (the smaller of its ends').
    pub fn edge(&self, s: &Soup, a: u32, b: u32) -> f64 {
        self.at(s.x[a as usize]).min(self.at(s.x[b as usize]))
    }
}
