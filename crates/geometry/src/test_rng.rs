//! A small reproducible random source for the crate's unit tests (xorshift64*): the geometry
//! crate does not depend on `sampling`, and its tests need nothing better.

use glam::{Vec3, Vec3A};

/// xorshift64* seeded with its state (which must not be zero).
pub(crate) struct TestRng(pub u64);

impl TestRng {
    /// A number in [0, 1) with 24 random bits.
    pub fn f32(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A point in [-1, 1)³.
    pub fn vec(&mut self) -> Vec3 {
        Vec3::new(self.f32(), self.f32(), self.f32()) * 2.0 - 1.0
    }

    /// [`TestRng::vec`] as a `Vec3A`.
    pub fn vec_a(&mut self) -> Vec3A {
        self.vec().into()
    }
}
