//! What a rendered surface looks like, independent of its part: an asset's own materials
//! (OBJ/MTL colours and `map_Kd` textures, URDF colours; `assets::surface`) where it
//! has them, and otherwise one procedural material per object: a colour pair blended by a
//! solid texture evaluated at the link's rest-frame position (so the texture moves with the
//! part and repeats between states and views). Lit by a fixed set of directional lights.
//!
//! Light model: Lambertian, two-sided, no shadows, no specular term. The radiance of a
//! surface point with albedo `a` and unit normal `n` (turned towards the camera) is
//! `a * min(1, ambient + sum_i intensity_i * max(0, n . l_i))`, with the light directions
//! `l_i` fixed in the object frame (they do not follow the camera), written to 8 bits
//! without gamma.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;
use serde::{Deserialize, Serialize};

use parry3d::query::PointQueryWithLocation;
use parry3d::shape::TriMesh;

use articulated::seed::Rng;
use assets::surface::Surface;

/// One surface material: colour `base` where the texture is low, `vein` where it is high.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Material {
    /// Albedo where the texture is 0, linear RGB in [0, 1].
    pub base: [Real; 3],
    /// Albedo where the texture is 1.
    pub vein: [Real; 3],
    /// Texture cycles per object unit (0: a uniform colour).
    pub frequency: Real,
    /// Seed of the texture's lattice.
    pub pattern: u32,
}

impl Material {
    /// A uniform colour, no texture.
    pub fn uniform(colour: [Real; 3]) -> Self {
        Self { base: colour, vein: colour, frequency: 0.0, pattern: 0 }
    }

    /// A random material for an object of bounding-box diagonal `diagonal`: a hue, a darker
    /// or lighter second colour of a nearby hue, and a texture of about six cycles across
    /// the object.
    pub fn draw(rng: &mut Rng, diagonal: Real) -> Self {
        let hue = rng.random_range(0.0..360.0);
        let saturation = rng.random_range(0.25..0.7);
        let value = rng.random_range(0.55..0.9);
        let base = hsv(hue, saturation, value);
        let vein = hsv(
            hue + rng.random_range(-40.0..40.0),
            (saturation + rng.random_range(-0.2..0.2)).clamp(0.1, 0.9),
            value * rng.random_range(0.35..0.65),
        );
        let cycles = rng.random_range(4.0..8.0);
        Self { base, vein, frequency: cycles / diagonal.max(1e-6), pattern: rng.random() }
    }

    /// Albedo at a rest-frame point.
    pub fn albedo(&self, rest: &Point3) -> [Real; 3] {
        if self.frequency <= 0.0 {
            return self.base;
        }
        let p = rest.coords * self.frequency;
        // Two octaves of marble-like bands plus a fine grain.
        let t =
            0.65 * value_noise(&p, self.pattern) + 0.35 * value_noise(&(p * 2.3), !self.pattern);
        let t = smoothstep(0.3, 0.7, t);
        let grain = 0.08 * (value_noise(&(p * 9.0), self.pattern ^ 0x9e37_79b9) - 0.5);
        std::array::from_fn(|c| {
            ((self.base[c] * (1.0 - t) + self.vein[c] * t) * (1.0 + grain)).clamp(0.0, 1.0)
        })
    }
}

/// The materials of an object's links: a procedural material per link, and where an asset
/// gives its own (OBJ/MTL colours and textures, URDF colours), the asset's.
#[derive(Debug, Clone, Serialize)]
pub struct Appearance {
    /// The procedural materials.
    pub materials: Vec<Material>,
    /// Procedural material of each link, an index into `materials`.
    pub material_of_link: Vec<usize>,
    /// The asset's own materials of each link (names, for the record), where it has any.
    pub asset_materials: Vec<Vec<String>>,
    /// Per link, the asset's styled triangles (`None` where it has none).
    #[serde(skip)]
    surfaces: Vec<Option<StyledLink>>,
}

/// One link's styled triangles, ready for point queries.
#[derive(Debug, Clone)]
struct StyledLink {
    soup: TriMesh,
    surface: Surface,
}

impl Appearance {
    /// One material for every link.
    pub fn single(material: Material, links: usize) -> Self {
        Self {
            materials: vec![material],
            material_of_link: vec![0; links],
            asset_materials: vec![Vec::new(); links],
            surfaces: vec![None; links],
        }
    }

    /// Adds an asset's surfaces (one per link, rest frame): a link with any material is
    /// shaded by them, its other triangles by its procedural material.
    pub fn with_surfaces(mut self, surfaces: &[Surface]) -> Self {
        for (link, surface) in surfaces.iter().enumerate().take(self.surfaces.len()) {
            if !surface.is_styled() {
                continue;
            }
            let vertices: Vec<Point3> = surface.corners.iter().flatten().copied().collect();
            let triangles: Vec<[u32; 3]> =
                (0..surface.corners.len() as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
            let Ok(soup) = TriMesh::new(vertices, triangles) else { continue };
            let mut names: Vec<String> =
                surface.material.iter().flatten().map(|m| m.name.clone()).collect();
            names.sort();
            names.dedup();
            self.asset_materials[link] = names;
            self.surfaces[link] = Some(StyledLink { soup, surface: surface.clone() });
        }
        self
    }

    /// Albedo of `link` at a rest-frame point: the asset's material of the nearest styled
    /// triangle (its texture sampled at the point's texture coordinates), else the link's
    /// procedural material.
    pub fn albedo(&self, link: usize, rest: &Point3) -> [Real; 3] {
        if let Some(styled) = &self.surfaces[link] {
            let (_, (triangle, location)) =
                styled.soup.project_local_point_and_get_location(rest, false);
            let t = triangle as usize;
            if let Some(material) = &styled.surface.material[t] {
                let uv = styled.surface.uv[t].map(|uv| {
                    let w = location.barycentric_coordinates().unwrap_or([1.0 / 3.0; 3]);
                    std::array::from_fn(|c| w[0] * uv[0][c] + w[1] * uv[1][c] + w[2] * uv[2][c])
                });
                return material.albedo(uv);
            }
        }
        self.materials[self.material_of_link[link]].albedo(rest)
    }
}

/// A directional light: unit direction towards the light (object frame) and intensity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DirectionalLight {
    /// Direction towards the light, object frame (need not be unit length).
    pub direction: [f64; 3],
    /// Intensity, a fraction of full white.
    pub intensity: f64,
}

/// The light model's parameters (see the module's documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Lighting {
    /// Light reaching every surface whatever its orientation.
    pub ambient: f64,
    /// Directional lights, fixed in the object frame (+y is up).
    pub lights: Vec<DirectionalLight>,
}

impl Default for Lighting {
    /// A key light from above and in front (+z), a weaker fill from the other side.
    fn default() -> Self {
        Self {
            ambient: 0.3,
            lights: vec![
                DirectionalLight { direction: [0.35, 1.0, 0.6], intensity: 0.55 },
                DirectionalLight { direction: [-0.6, 0.3, -0.5], intensity: 0.3 },
            ],
        }
    }
}

impl Lighting {
    /// The fraction of its albedo a surface with unit normal `normal` sends back.
    pub fn irradiance(&self, normal: &Vector3) -> Real {
        let direct: f64 = self
            .lights
            .iter()
            .map(|l| {
                let d = Vector3::new(
                    l.direction[0] as Real,
                    l.direction[1] as Real,
                    l.direction[2] as Real,
                );
                let d = pairs::math::unit_or(&d, Vector3::y());
                l.intensity * f64::from(normal.dot(&d).max(0.0))
            })
            .sum();
        (self.ambient + direct).clamp(0.0, 1.0) as Real
    }
}

/// Colour of a hue (degrees), saturation and value, RGB in [0, 1].
fn hsv(hue: Real, saturation: Real, value: Real) -> [Real; 3] {
    let h = hue.rem_euclid(360.0) / 60.0;
    let c = value * saturation;
    let x = c * (1.0 - (h % 2.0 - 1.0).abs());
    let (r, g, b) = match h as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = value - c;
    [r + m, g + m, b + m]
}

fn smoothstep(lo: Real, hi: Real, x: Real) -> Real {
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Trilinear value noise in [0, 1]: a hashed value per integer lattice point, blended
/// with smooth weights.
fn value_noise(p: &Vector3, seed: u32) -> Real {
    let cell = p.map(|x| x.floor());
    let f = p - cell;
    let w = f.map(|t| t * t * (3.0 - 2.0 * t));
    let (i, j, k) = (cell.x as i32, cell.y as i32, cell.z as i32);
    let v = |a: i32, b: i32, c: i32| lattice(i + a, j + b, k + c, seed);
    let lerp = |a: Real, b: Real, t: Real| a + (b - a) * t;
    let x00 = lerp(v(0, 0, 0), v(1, 0, 0), w.x);
    let x10 = lerp(v(0, 1, 0), v(1, 1, 0), w.x);
    let x01 = lerp(v(0, 0, 1), v(1, 0, 1), w.x);
    let x11 = lerp(v(0, 1, 1), v(1, 1, 1), w.x);
    lerp(lerp(x00, x10, w.y), lerp(x01, x11, w.y), w.z)
}

/// A value in [0, 1) per lattice point and seed (a 32-bit integer hash).
fn lattice(i: i32, j: i32, k: i32, seed: u32) -> Real {
    let mut h = seed ^ (i as u32).wrapping_mul(0x8da6_b343);
    h ^= (j as u32).wrapping_mul(0xd816_3841);
    h ^= (k as u32).wrapping_mul(0xcb1a_b31f);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^= h >> 16;
    (h >> 8) as Real / (1u32 << 24) as Real
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn the_texture_varies_within_its_colours_and_repeats() {
        let m = Material::draw(&mut Rng::seed_from_u64(4), 1.0);
        let samples: Vec<[Real; 3]> =
            (0..200).map(|i| m.albedo(&Point3::new(i as Real * 0.013, 0.1, -0.2))).collect();
        let reds: Vec<Real> = samples.iter().map(|c| c[0]).collect();
        let spread = reds.iter().cloned().fold(Real::MIN, Real::max)
            - reds.iter().cloned().fold(Real::MAX, Real::min);
        assert!(spread > 0.05, "a texture, not a flat colour: spread {spread}");
        assert!(samples.iter().flatten().all(|c| (0.0..=1.0).contains(c)));
        assert_eq!(m.albedo(&Point3::new(0.3, 0.2, 0.1)), m.albedo(&Point3::new(0.3, 0.2, 0.1)));
        let flat = Material::uniform([0.2, 0.4, 0.6]);
        assert_eq!(flat.albedo(&Point3::new(5.0, -3.0, 1.0)), [0.2, 0.4, 0.6]);
    }

    #[test]
    fn lambert_with_ambient_on_hand_computed_normals() {
        let lighting = Lighting {
            ambient: 0.2,
            lights: vec![DirectionalLight { direction: [0.0, 2.0, 0.0], intensity: 0.5 }],
        };
        assert!((lighting.irradiance(&Vector3::y()) - 0.7).abs() < 1e-6);
        assert!((lighting.irradiance(&-Vector3::y()) - 0.2).abs() < 1e-6);
        let tilted = Vector3::new(0.0, 0.5, 0.75f32.sqrt());
        assert!((lighting.irradiance(&tilted) - 0.45).abs() < 1e-6);
    }

    #[test]
    fn hsv_primaries() {
        assert_eq!(hsv(0.0, 1.0, 1.0), [1.0, 0.0, 0.0]);
        assert_eq!(hsv(120.0, 1.0, 1.0), [0.0, 1.0, 0.0]);
        assert_eq!(hsv(240.0, 1.0, 0.5), [0.0, 0.0, 0.5]);
        assert_eq!(hsv(77.0, 0.0, 0.25), [0.25, 0.25, 0.25]);
    }
}
