//! Which spheres a moved sphere's shadow can fall on: the shadow receivers of the rule's
//! step 2.

use crate::math::vec3::Vec3;
use crate::scene::light::Light;
use crate::scene::sphere::Sphere;

/// Whether sphere `k` can lie between a point of sphere `j` and `light`: whether `k`'s
/// shadow can fall on `j`.
///
/// Exact geometry in `f64` with both radii enlarged by `2⁻⁸` of the lengths involved (as
/// the shadow silhouettes are; the kernel's shadow test is within about `2⁻²²` of them):
/// - directional light (toward it `u`): `j`'s cylinder along `u` meets `k`, i.e. `k`'s
///   centre lies within `r_j + r_k` of the line through `j`'s centre along `u`, not
///   behind it;
/// - point light `P`: the cones from `P` around the two spheres overlap (angle between
///   their axes below the sum of their half-angles) and `j` reaches beyond `k`'s near
///   side; a light inside either sphere is always a yes.
pub(super) fn can_shadow(k: &Sphere, j: &Sphere, light: &Light) -> bool {
    let v = |a: Vec3| [f64::from(a.x), f64::from(a.y), f64::from(a.z)];
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (ck, cj) = (v(k.center), v(j.center));
    let (rk, rj) = (f64::from(k.radius), f64::from(j.radius));
    match *light {
        Light::Directional { direction, .. } => {
            let d = v(direction);
            let len = libm::sqrt(dot(d, d));
            let u = [-d[0] / len, -d[1] / len, -d[2] / len];
            let w = sub(ck, cj);
            let dist = libm::sqrt(dot(w, w));
            let reach = (rk + rj) * (1.0 + 1.0 / 256.0) + dist / 256.0;
            let along = dot(w, u);
            let perp2 = dot(w, w) - along * along;
            // NaN (a zero direction) is a yes.
            !(along < -reach || perp2 > reach * reach)
        }
        Light::Point { position, .. } => {
            let p = v(position);
            let (wk, wj) = (sub(ck, p), sub(cj, p));
            let (dk, dj) = (libm::sqrt(dot(wk, wk)), libm::sqrt(dot(wj, wj)));
            let (mk, mj) = ((dk + rk) / 256.0, (dj + rj) / 256.0);
            let (rk, rj) = (rk + mk, rj + mj);
            if !(dk > rk && dj > rj) {
                return true;
            }
            let half = |r: f64, d: f64| libm::asin(r / d);
            let cos = (dot(wk, wj) / (dk * dj)).clamp(-1.0, 1.0);
            let theta = libm::acos(cos);
            !(theta > half(rk, dk) + half(rj, dj) + 1e-9 || dj + rj < dk - rk)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::Rgb888;

    fn ball(y: f32) -> Sphere {
        Sphere::new(Vec3::new(0.0, y, 0.0), 1.0, Rgb888::new(255, 255, 255))
    }

    #[test]
    fn under_the_sun_only_a_sphere_toward_it_shadows() {
        let sun = Light::directional(Vec3::new(0.0, -1.0, 0.0), 1.0);
        assert!(can_shadow(&ball(3.0), &ball(0.0), &sun));
        assert!(!can_shadow(&ball(-3.0), &ball(0.0), &sun));
        let aside = Sphere::new(Vec3::new(5.0, 3.0, 0.0), 1.0, Rgb888::new(255, 255, 255));
        assert!(!can_shadow(&aside, &ball(0.0), &sun));
        // A zero direction decides nothing: a yes.
        let none = Light::directional(Vec3::ZERO, 1.0);
        assert!(can_shadow(&aside, &ball(0.0), &none));
    }

    #[test]
    fn under_a_lamp_only_a_sphere_between_shadows() {
        let lamp = Light::point(Vec3::new(0.0, 10.0, 0.0), 1.0);
        assert!(can_shadow(&ball(5.0), &ball(0.0), &lamp));
        assert!(!can_shadow(&ball(-5.0), &ball(0.0), &lamp));
        // A lamp inside either sphere is always a yes.
        let inside = Light::point(Vec3::new(0.0, 0.5, 0.0), 1.0);
        assert!(can_shadow(&ball(-5.0), &ball(0.0), &inside));
    }
}
