//! Floating-point measures of the output (volumes).

/// Signed volume contribution `sum det(x0, xi, xi+1) / 6` of a planar loop
/// (the divergence theorem term for the loop's normal side).
pub fn loop_volume(x: &[[f64; 3]], verts: &[u32]) -> f64 {
    let o = x[verts[0] as usize];
    let mut s = 0.0;
    for i in 1..verts.len().saturating_sub(1) {
        let a = x[verts[i] as usize];
        let b = x[verts[i + 1] as usize];
        // relative to o for accuracy; the closed surface sum is unchanged
        let (a, b) = ([a[0] - o[0], a[1] - o[1], a[2] - o[2]], [b[0] - o[0], b[1] - o[1], b[2] - o[2]]);
        let cr = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        s += cr[0] * o[0] + cr[1] * o[1] + cr[2] * o[2];
    }
    s / 6.0
}

/// Signed volume of a closed triangle mesh.
pub fn mesh_volume(x: &[[f64; 3]], tris: &[[u32; 3]]) -> f64 {
    tris.iter().map(|t| loop_volume(x, t)).sum()
}

/// The floating-point embedding heuristic of TopoCut Sec. 6.1: along one
/// intersection line with exactly ordered vertices `line`, every step must
/// advance along the line direction; a vertex that does not is pushed
/// forward along the direction by the smallest power-of-two multiple of its
/// ulp that restores the order. Returns the vertices moved.
pub fn enforce_line_order(x: &mut [[f64; 3]], line: &[u32], moved: &mut Vec<u32>) {
    if line.len() < 2 {
        return;
    }
    let (a, b) = (x[line[0] as usize], x[line[line.len() - 1] as usize]);
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if n.is_nan() || n <= 0.0 {
        return;
    }
    let t = [d[0] / n, d[1] / n, d[2] / n];
    let dot = |p: [f64; 3], q: [f64; 3]| (q[0] - p[0]) * t[0] + (q[1] - p[1]) * t[1] + (q[2] - p[2]) * t[2];
    for w in line.windows(2) {
        let p = x[w[0] as usize];
        let mut q = x[w[1] as usize];
        if dot(p, q) > 0.0 {
            continue;
        }
        let scale = q.iter().fold(f64::MIN_POSITIVE, |m, c| m.max(c.abs())) * f64::EPSILON;
        let mut step = scale;
        for _ in 0..64 {
            let r = [q[0] + t[0] * step, q[1] + t[1] * step, q[2] + t[2] * step];
            if dot(p, r) > 0.0 {
                q = r;
                break;
            }
            step *= 2.0;
        }
        x[w[1] as usize] = q;
        moved.push(w[1]);
    }
}
