//! The 8-wide BVH node and its conservative ray test against all eight child boxes at once.
//!
//! The child boxes are stored by plane (`min_x` of four children in one vector, and so on), so
//! two passes of 4-lane vector operations test all of them. The test clamps the entry distance
//! to `0` (surfaces just in front of the origin are found, however close) and widens every slab
//! by a bound on its rounding error (a ray grazing a box face, where the extreme primitive of the
//! box lies, is never rejected); see [`super::query::BoxRay`].

use glam::Vec4;

use super::query::BoxRay;

/// A reference to a child: an inner node, a packet of one to four triangles, or one sphere.
///
/// Bit 31 marks leaves and bit 30 spheres among them; bits 28 and 29 hold a triangle packet's
/// number of triangles less one, and the bits below the index of the node, packet or sphere.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ChildRef(u32);

/// What a [`ChildRef`] refers to, by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Child {
    Node(usize),
    /// A packet and the bitmask of its lanes in use (bit `i` for lane `i`).
    Triangles {
        packet: usize,
        lanes: u32,
    },
    Sphere(usize),
}

impl ChildRef {
    const LEAF: u32 = 1 << 31;
    const SPHERE: u32 = 1 << 30;
    const COUNT_SHIFT: u32 = 28;
    /// One more than the largest index of any kind.
    pub const MAX_INDEX: usize = 1 << Self::COUNT_SHIFT;
    /// The child of an unused slot, whose box no ray hits: it is never followed (and would
    /// refer to a sphere index no scene reaches).
    pub const EMPTY: ChildRef = ChildRef(u32::MAX);

    /// The inner node `index`.
    pub fn node(index: usize) -> Self {
        Self::new(0, index)
    }

    /// The first `count` (one to four) lanes of triangle packet `index`.
    pub fn triangles(index: usize, count: usize) -> Self {
        assert!((1..=4).contains(&count), "a packet of {count} triangles");
        Self::new(
            Self::LEAF | ((count as u32 - 1) << Self::COUNT_SHIFT),
            index,
        )
    }

    /// The sphere `index`.
    pub fn sphere(index: usize) -> Self {
        Self::new(Self::LEAF | Self::SPHERE, index)
    }

    fn new(kind: u32, index: usize) -> Self {
        assert!(
            index < Self::MAX_INDEX,
            "index {index} does not fit a child reference"
        );
        ChildRef(kind | index as u32)
    }

    /// What this refers to.
    #[inline(always)]
    pub fn get(self) -> Child {
        if self.0 & Self::LEAF == 0 {
            Child::Node(self.0 as usize)
        } else if self.0 & Self::SPHERE == 0 {
            let count_less_one = (self.0 >> Self::COUNT_SHIFT) & 3;
            Child::Triangles {
                packet: (self.0 & (Self::MAX_INDEX as u32 - 1)) as usize,
                lanes: (2 << count_less_one) - 1,
            }
        } else {
            Child::Sphere((self.0 & (Self::MAX_INDEX as u32 - 1)) as usize)
        }
    }

    /// The inner node's index, if this refers to one.
    #[inline(always)]
    pub fn inner(self) -> Option<usize> {
        match self.get() {
            Child::Node(index) => Some(index),
            _ => None,
        }
    }
}

impl Default for ChildRef {
    fn default() -> Self {
        ChildRef::EMPTY
    }
}

/// Children per node. Eight rather than four halves the levels a ray descends (measured against
/// four: the Cornell box's closest-hit and shadow rays 14–15% faster, the 1.3M-triangle icosphere's
/// 3% and 15–26%; 5–18% slower where every leaf fits the root, as in Veach's scene and the
/// furnace; README, "The wide BVH").
pub(crate) const WIDTH: usize = 8;

/// Four-lane vectors per plane of a node.
const QUARTETS: usize = WIDTH / 4;

/// [`WIDTH`] child boxes and what they hold. Unused slots have the empty box (`min = +inf`,
/// `max = -inf`), which no ray hits, and [`ChildRef::EMPTY`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct Node {
    /// `min_x, max_x, min_y, max_y, min_z, max_z`, each over the children, four to a vector:
    /// lane `l` of `planes[k][q]` belongs to child `4 q + l`.
    pub planes: [[Vec4; QUARTETS]; 6],
    pub children: [ChildRef; WIDTH],
}

impl Node {
    /// A node with every slot unused.
    pub const EMPTY: Node = Node {
        planes: [
            [Vec4::INFINITY; QUARTETS],
            [Vec4::NEG_INFINITY; QUARTETS],
            [Vec4::INFINITY; QUARTETS],
            [Vec4::NEG_INFINITY; QUARTETS],
            [Vec4::INFINITY; QUARTETS],
            [Vec4::NEG_INFINITY; QUARTETS],
        ],
        children: [ChildRef::EMPTY; WIDTH],
    };

    /// Plane `plane` (as in [`Node::planes`]) of the box in slot `lane`.
    #[cfg(test)]
    pub fn plane(&self, plane: usize, lane: usize) -> f32 {
        self.planes[plane][lane / 4][lane % 4]
    }

    /// Puts the box `min`..`max`, grown by one float step on every side, with content `child`
    /// in slot `lane`.
    ///
    /// Growing keeps a ray that lies in a plane of the box (a zero direction component, the
    /// origin on the plane) from computing `0 * inf`: such a ray is then strictly inside the
    /// slab, even for a box of zero thickness (a flat quad's), or strictly outside it.
    pub fn set(&mut self, lane: usize, min: [f32; 3], max: [f32; 3], child: ChildRef) {
        for axis in 0..3 {
            self.planes[2 * axis][lane / 4][lane % 4] = min[axis].next_down();
            self.planes[2 * axis + 1][lane / 4][lane % 4] = max[axis].next_up();
        }
        self.children[lane] = child;
    }

    /// Which children the ray may hit at `0 <= t <= t_max` (bit `i` for child `i`), and the
    /// (conservatively small) distances at which it enters their boxes.
    #[inline(always)]
    pub fn hit(&self, ray: &BoxRay, t_max: f32) -> (u32, [f32; WIDTH]) {
        let mut mask = 0;
        let mut t_enters = [0.0; WIDTH];
        for quartet in 0..QUARTETS {
            let slab = |axis: usize| {
                // The planes the ray enters and leaves the slab through; `& 1` lets the compiler
                // see that both indices are in bounds.
                let flip = ray.flip[axis] & 1;
                let entry = self.planes[2 * axis + flip][quartet];
                let exit = self.planes[2 * axis + (flip ^ 1)][quartet];
                (
                    (entry - ray.origin[axis]) * ray.inv_entry[axis],
                    (exit - ray.origin[axis]) * ray.inv_exit[axis],
                )
            };
            let (x0, x1) = slab(0);
            let (y0, y1) = slab(1);
            let (z0, z1) = slab(2);
            let t_enter = x0.max(y0).max(z0).max(Vec4::ZERO);
            let t_exit = x1.min(y1).min(z1).min(Vec4::splat(t_max));
            mask |= t_enter.cmple(t_exit).bitmask() << (4 * quartet);
            t_enters[4 * quartet..4 * quartet + 4].copy_from_slice(&t_enter.to_array());
        }
        (mask, t_enters)
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3A;

    use super::*;
    use crate::accel::query::RayQuery;
    use crate::test_rng::TestRng;

    /// In `[-1, 1)`, with exact zeros and exact box coordinates now and then.
    fn coord(rng: &mut TestRng, snap: f32) -> f32 {
        let u = rng.f32();
        if u < 0.1 { snap } else { 2.0 * rng.f32() - 1.0 }
    }

    /// Whether the ray meets the box at some `0 <= t <= t_max`, in double precision (the
    /// ray's own `f32` origin and direction, exactly).
    fn exact_hit(origin: Vec3A, dir: Vec3A, min: [f32; 3], max: [f32; 3], t_max: f32) -> bool {
        let (mut enter, mut exit) = (0.0f64, f64::from(t_max));
        for axis in 0..3 {
            let (o, d) = (f64::from(origin[axis]), f64::from(dir[axis]));
            let (lo, hi) = (f64::from(min[axis]), f64::from(max[axis]));
            if d == 0.0 {
                if o < lo || o > hi {
                    return false;
                }
                continue;
            }
            let (a, b) = ((lo - o) / d, (hi - o) / d);
            enter = enter.max(a.min(b));
            exit = exit.min(a.max(b));
        }
        enter <= exit
    }

    #[test]
    fn child_refs_round_trip() {
        let last = ChildRef::MAX_INDEX - 1;
        for index in [0, 1, 12345, last] {
            assert_eq!(ChildRef::node(index).get(), Child::Node(index));
            for (count, lanes) in [(1, 0b1), (2, 0b11), (3, 0b111), (4, 0b1111)] {
                let packet = ChildRef::triangles(index, count).get();
                assert_eq!(
                    packet,
                    Child::Triangles {
                        packet: index,
                        lanes
                    }
                );
            }
            assert_eq!(ChildRef::sphere(index).get(), Child::Sphere(index));
            assert_eq!(ChildRef::node(index).inner(), Some(index));
            assert_eq!(ChildRef::sphere(index).inner(), None);
        }
        assert_eq!(ChildRef::EMPTY.get(), Child::Sphere(last));
    }

    #[test]
    fn unused_slots_are_never_hit() {
        let node = Node::EMPTY;
        for dir in [
            Vec3A::X,
            Vec3A::NEG_Y,
            Vec3A::new(0.0, -0.0, 1.0),
            Vec3A::ONE,
        ] {
            let ray = RayQuery::new(Vec3A::ZERO, dir.normalize());
            assert_eq!(node.hit(&ray.boxes, f32::INFINITY).0, 0, "{dir}");
        }
    }

    #[test]
    fn rays_in_the_plane_of_a_flat_box_hit_it() {
        let mut node = Node::EMPTY;
        node.set(5, [-1.0, -1.0, 0.0], [1.0, 1.0, 0.0], ChildRef::node(1));
        for (origin, dir) in [
            (Vec3A::new(-2.0, 0.5, 0.0), Vec3A::X),
            (
                Vec3A::new(0.0, 0.0, 0.0),
                Vec3A::new(1.0, -1.0, 0.0).normalize(),
            ),
            (Vec3A::new(1.0, 3.0, -0.0), Vec3A::NEG_Y),
        ] {
            let ray = RayQuery::new(origin, dir);
            assert_eq!(
                node.hit(&ray.boxes, f32::INFINITY).0,
                1 << 5,
                "{origin} + t {dir}"
            );
            // Beside the box, in its plane.
            let beside = RayQuery::new(origin + Vec3A::new(0.0, 0.0, 1e-3), dir);
            assert_eq!(
                node.hit(&beside.boxes, f32::INFINITY).0,
                0,
                "{origin} + t {dir}"
            );
        }
    }

    /// Every box the ray meets in exact arithmetic passes the test, including boxes the ray only
    /// grazes, touches at a corner, or starts on, and rays along the axes.
    #[test]
    fn box_test_is_conservative() {
        let seed = 0x5eed_0010;
        let mut rng = TestRng(seed);
        let mut hits = 0;
        for i in 0..200_000 {
            let mut min = [0.0; 3];
            let mut max = [0.0; 3];
            for axis in 0..3 {
                let (a, b) = (coord(&mut rng, 0.0), coord(&mut rng, 0.0));
                (min[axis], max[axis]) = (a.min(b), a.max(b));
            }
            // Origins on a face plane or an edge now and then; directions with zero components.
            let origin = Vec3A::from([0, 1, 2].map(|axis| 2.0 * coord(&mut rng, min[axis])));
            // Mostly aimed at a point of the box (often on its boundary), with components
            // zeroed now and then; some in any direction.
            let dir = if i % 8 == 0 {
                Vec3A::from([0, 1, 2].map(|_| coord(&mut rng, 0.0)))
            } else {
                let target = [0, 1, 2].map(|axis| {
                    let u = rng.f32();
                    let inside = min[axis] + (max[axis] - min[axis]) * rng.f32();
                    if u < 0.2 {
                        min[axis]
                    } else if u < 0.4 {
                        max[axis]
                    } else {
                        inside
                    }
                });
                let aim = Vec3A::from(target) - origin;
                Vec3A::from([0, 1, 2].map(|axis| if rng.f32() < 0.1 { 0.0 } else { aim[axis] }))
            };
            if dir == Vec3A::ZERO {
                continue;
            }
            let dir = dir.normalize();
            let t_max = if i % 4 == 0 {
                3.0 * rng.f32()
            } else {
                f32::INFINITY
            };
            // A slot in the first quartet and one in the last, by turns.
            let lane = if i % 2 == 0 { 2 } else { WIDTH - 2 };
            let mut node = Node::EMPTY;
            node.set(lane, min, max, ChildRef::node(1));
            let ray = RayQuery::new(origin, dir);
            let (mask, t_enter) = node.hit(&ray.boxes, t_max);
            if exact_hit(origin, dir, min, max, t_max) {
                hits += 1;
                assert_eq!(
                    mask,
                    1 << lane,
                    "seed {seed:#x}, case {i}: box {min:?}..{max:?} in slot {lane} missed by {origin} + t {dir}, t_max {t_max}"
                );
                assert!(t_enter[lane] >= 0.0);
            }
        }
        assert!(hits > 50_000, "only {hits} boxes were hit");
    }
}
