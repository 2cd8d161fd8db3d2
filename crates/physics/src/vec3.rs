//! 3-vectors `[x, y, z]` and the few operations the 3-D rebound needs, inlined everywhere
//! (the rebound algebra and the lookup's prepared pairs use these same functions, so both do
//! the same floating-point operations in the same order).

/// A 3-vector `[x, y, z]` in any right-handed frame (units of the quantity it holds).
pub type Vec3 = [f64; 3];

/// `a · b`.
#[inline(always)]
pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a × b`.
#[inline(always)]
pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `y + a x`.
#[inline(always)]
pub fn axpy(y: Vec3, a: f64, x: Vec3) -> Vec3 {
    [y[0] + a * x[0], y[1] + a * x[1], y[2] + a * x[2]]
}

/// `a x`.
#[inline(always)]
pub fn scale(a: f64, x: Vec3) -> Vec3 {
    [a * x[0], a * x[1], a * x[2]]
}

/// `a − b`.
#[inline(always)]
pub fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
