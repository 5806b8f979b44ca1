//! The shape model and its gravity (`touchdown::shape`) against closed forms: a sphere, a
//! cube, a far-away point mass, the gradient of the potential, a spinning sphere's slope,
//! each facet's roughness on the regular solids and icospheres; bad meshes and bad OBJ,
//! plate and ICQ files refused.

mod gravity;
mod icq;
mod intersect;
mod obj;
mod plate;
mod plate_refusals;
mod refusals;
mod roughness;
mod slope;
mod tree;

use std::collections::HashMap;
use touchdown::shape::{CheckedMesh, Mesh};

/// The icosahedron subdivided `levels` times (each triangle into four, the new vertices
/// pushed out onto the sphere): every vertex on the sphere of radius `radius_m` about the
/// origin, facets counter-clockwise from outside.
pub fn icosphere(radius_m: f64, levels: u32) -> Mesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut vertices: Vec<[f64; 3]> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .to_vec();
    let mut facets: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut middle: HashMap<(u32, u32), u32> = HashMap::new();
        let mut mid = |a: u32, b: u32, vertices: &mut Vec<[f64; 3]>| {
            *middle.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (vertices[a as usize], vertices[b as usize]);
                vertices.push([
                    (p[0] + q[0]) / 2.0,
                    (p[1] + q[1]) / 2.0,
                    (p[2] + q[2]) / 2.0,
                ]);
                vertices.len() as u32 - 1
            })
        };
        let mut next = Vec::with_capacity(4 * facets.len());
        for &[a, b, c] in &facets {
            let ab = mid(a, b, &mut vertices);
            let bc = mid(b, c, &mut vertices);
            let ca = mid(c, a, &mut vertices);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        facets = next;
    }
    for v in &mut vertices {
        let r = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        *v = v.map(|x| x * radius_m / r);
    }
    Mesh { vertices, facets }
}

/// A latitude-longitude sphere of `bands` bands and `sectors` sectors: `2 sectors (bands -
/// 1)` facets.
pub fn uv_sphere(radius_m: f64, bands: u32, sectors: u32) -> Mesh {
    let mut vertices = vec![[0.0, 0.0, radius_m]];
    for i in 1..bands {
        let polar = std::f64::consts::PI * f64::from(i) / f64::from(bands);
        for j in 0..sectors {
            let lon = 2.0 * std::f64::consts::PI * f64::from(j) / f64::from(sectors);
            vertices.push([
                radius_m * polar.sin() * lon.cos(),
                radius_m * polar.sin() * lon.sin(),
                radius_m * polar.cos(),
            ]);
        }
    }
    vertices.push([0.0, 0.0, -radius_m]);
    let south = vertices.len() as u32 - 1;
    let ring = |i: u32, j: u32| 1 + (i - 1) * sectors + j % sectors;
    let mut facets = Vec::new();
    for j in 0..sectors {
        facets.push([0, ring(1, j), ring(1, j + 1)]);
        facets.push([south, ring(bands - 1, j + 1), ring(bands - 1, j)]);
    }
    for i in 1..bands - 1 {
        for j in 0..sectors {
            let (a, b, c, d) = (
                ring(i, j),
                ring(i + 1, j),
                ring(i + 1, j + 1),
                ring(i, j + 1),
            );
            facets.push([a, b, c]);
            facets.push([a, c, d]);
        }
    }
    Mesh { vertices, facets }
}

/// A box of half-sides `a`, `b`, `c` (m): its top face turned by `twist_deg` about z and
/// shrunk by `taper`, then the whole shifted by `offset` (m). Its quads are split into two
/// triangles each (12 facets); with no twist, taper 1 and no offset, a box about the origin.
pub fn twisted_box(a: f64, b: f64, c: f64, twist_deg: f64, taper: f64, offset: [f64; 3]) -> Mesh {
    let (s, k) = twist_deg.to_radians().sin_cos();
    let corners = [[-a, -b], [a, -b], [a, b], [-a, b]];
    let mut vertices = Vec::new();
    for [x, y] in corners {
        vertices.push([x + offset[0], y + offset[1], -c + offset[2]]);
    }
    for [x, y] in corners {
        let (x, y) = (taper * (k * x - s * y), taper * (s * x + k * y));
        vertices.push([x + offset[0], y + offset[1], c + offset[2]]);
    }
    let quads = [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
    ];
    let facets = quads
        .iter()
        .flat_map(|&[p, q, r, t]| [[p, q, r], [p, r, t]])
        .collect();
    Mesh { vertices, facets }
}

/// The cube `[-h, h]^3`.
pub fn cube(h: f64) -> Mesh {
    twisted_box(h, h, h, 0.0, 1.0, [0.0; 3])
}

/// The mesh, checked (a test's own meshes are all sound).
pub fn checked(mesh: Mesh) -> CheckedMesh {
    mesh.check().expect("a sound test mesh")
}

/// The largest depth of a facet below the sphere of radius `radius_m` about the origin
/// that holds the mesh's vertices: the sagitta `R - n . c` of the deepest facet plane.
pub fn sagitta_m(mesh: &CheckedMesh, radius_m: f64) -> f64 {
    mesh.facet_geometry()
        .iter()
        .map(|g| radius_m - dot(g.normal, g.centroid_m))
        .fold(0.0, f64::max)
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    a.map(|x| x * s)
}

pub fn unit(a: [f64; 3]) -> [f64; 3] {
    scale(a, 1.0 / norm(a))
}

pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// xorshift64*: a seeded stream of test inputs (the shape readers' fuzz tests).
pub struct Stream(pub u64);

impl Stream {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The mutations of a shape reader's fuzz test, drawn from `s`: each sound file of `files`
/// with 1 to 4 of its bytes replaced by `bytes` (`rounds[0]` times), 1 to 3 of its words by
/// `words` (`rounds[1]`), a line removed, repeated or swapped (`rounds[2]`), and cut at every
/// byte (only the whole file, with or without its last newline, is sound: asserted); then
/// `rounds[3]` files of up to 200 random `bytes`. Each goes through `survive` (read, check,
/// evaluate, and whether it was sound: never a panic). Returns how many files with bytes
/// replaced were sound (some must be, or the mutations never reach the reader's end).
pub fn fuzz(
    s: &mut Stream,
    files: &[String],
    (bytes, words): (&[u8], &[&str]),
    rounds: [usize; 4],
    survive: impl Fn(&str) -> bool,
) -> usize {
    let mut sound = 0;
    for file in files {
        for _ in 0..rounds[0] {
            let mut b = file.as_bytes().to_vec();
            for _ in 0..1 + s.below(4) {
                let at = s.below(b.len());
                b[at] = bytes[s.below(bytes.len())];
            }
            if survive(&String::from_utf8_lossy(&b)) {
                sound += 1;
            }
        }
        for _ in 0..rounds[1] {
            let mut w: Vec<&str> = file.split(' ').collect();
            for _ in 0..1 + s.below(3) {
                let at = s.below(w.len());
                w[at] = words[s.below(words.len())];
            }
            survive(&w.join(" "));
        }
        let lines: Vec<&str> = file.split_inclusive('\n').collect();
        for _ in 0..rounds[2] {
            let mut l = lines.clone();
            let (i, j) = (s.below(l.len()), s.below(l.len()));
            match s.below(3) {
                0 => {
                    l.remove(i);
                }
                1 => l.insert(i, lines[j]),
                _ => l.swap(i, j),
            }
            survive(&l.concat());
        }
        let cut = (0..=file.len())
            .filter(|&n| file.is_char_boundary(n) && survive(&file[..n]))
            .count();
        let eol = if file.ends_with("\r\n") { 3 } else { 2 };
        assert_eq!(cut, eol, "{file}");
    }
    for _ in 0..rounds[3] {
        let b: Vec<u8> = (0..s.below(200))
            .map(|_| bytes[s.below(bytes.len())])
            .collect();
        survive(&String::from_utf8_lossy(&b));
    }
    sound
}
