//! Whether a tile's camera rays go as packets (see [`PacketGauge`]).

/// Whether a tile's camera rays still go as packets: they do while the
/// packets' walks test few leaves. A pixel's rays share their leaves
/// where the pixel is small against the scene's primitives (the mesh at
/// 512²: 3.8 blocks a packet, about a single ray's); where it covers many
/// primitives each ray tests the leaves of all (6.5 blocks at 256², 39 at
/// 64²), more than the shared walk saves (docs/performance.md, "Camera-ray
/// packets"). Which hits the rays get is the same either way.
pub(super) struct PacketGauge {
    /// Whether the tile's rays go as packets.
    pub(super) on: bool,
    packets: u32,
    leaf_tests: u32,
}

impl PacketGauge {
    /// Packets measured before the gauge may turn them off.
    const SETTLE: u32 = 8;
    /// The most leaves a packet's walk tests on average for packets to go on.
    const MOST_LEAF_TESTS: u32 = 10;

    /// A gauge starting `on` or off.
    pub(super) fn new(on: bool) -> PacketGauge {
        PacketGauge {
            on,
            packets: 0,
            leaf_tests: 0,
        }
    }

    /// Counts a packet whose walk tested `leaf_tests` leaves.
    pub(super) fn add(&mut self, leaf_tests: u32) {
        self.packets += 1;
        self.leaf_tests = self.leaf_tests.saturating_add(leaf_tests);
        if self.packets >= Self::SETTLE && self.leaf_tests > Self::MOST_LEAF_TESTS * self.packets {
            self.on = false;
        }
    }
}
