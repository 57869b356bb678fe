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
