//! proptest over the simulated bus: well-framed packets with arbitrary IDs, instructions and
//! parameters (and garbage between them), sent over the pty, never bring it down.

use dxl_sim::{CLOCK_INSTRUCTION, SimBus, SimConfig};
use hand_control::protocol::encode;
use proptest::prelude::*;

/// Instructions the simulator knows, plus a few it must refuse.
fn instruction() -> impl Strategy<Value = u8> {
    prop_oneof![
        prop::sample::select(vec![
            0x01u8, 0x02, 0x03, 0x04, 0x05, 0x06, 0x08, 0x10, 0x82, 0x83, 0x92, 0x93
        ]),
        any::<u8>().prop_filter("not the simulator's clock packet", |&i| i
            != CLOCK_INSTRUCTION),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Well-framed packets with arbitrary contents (and garbage between them) never bring the
    /// simulated bus down: it still acknowledges a clock packet afterwards.
    #[test]
    fn simulator_survives_arbitrary_packets(
        packets in prop::collection::vec(
            (prop_oneof![Just(1u8), Just(2), Just(0xFE), any::<u8>()], instruction(),
             prop::collection::vec(any::<u8>(), 0..24),
             prop::collection::vec(any::<u8>(), 0..8)),
            1..6),
    ) {
        let (mut sim, client) = SimBus::spawn(SimConfig::with_ids(&[1, 2])).expect("pty");
        let mut wire = Vec::new();
        for (id, ins, params, garbage) in &packets {
            encode(&mut wire, *id, *ins, params);
            wire.extend_from_slice(garbage);
        }
        client.write_all(&wire).expect("write");
        prop_assert!(sim.sync().is_ok(), "simulator stopped answering after {packets:?}");
    }
}
