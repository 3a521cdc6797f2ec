//! proptest over arbitrary byte streams: the packet parser never panics, and a valid packet
//! after any garbage is still found (resynchronisation).

use hand_control::protocol::{Parser, encode};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn never_panics_on_arbitrary_bytes(chunks in prop::collection::vec(prop::collection::vec(any::<u8>(), 0..64), 0..16)) {
        let mut p = Parser::default();
        for c in &chunks {
            p.push(c);
            while p.next_packet().is_some() {}
        }
        // Whatever is left is at most an unfinished frame.
        prop_assert!(p.pending() <= 7 + hand_control::protocol::MAX_LEN);
    }

    #[test]
    fn resynchronises_after_garbage(
        garbage in prop::collection::vec(prop_oneof![Just(0xFFu8), Just(0xFD), Just(0x00), any::<u8>()], 0..200),
        id in 0u8..=252,
        instruction in any::<u8>(),
        params in prop::collection::vec(prop_oneof![Just(0xFFu8), Just(0xFD), any::<u8>()], 0..40),
        split in any::<prop::sample::Index>(),
    ) {
        let mut wire = garbage.clone();
        let tail = wire.len();
        encode(&mut wire, id, instruction, &params);
        // Garbage that opens a frame with a long length would swallow the packet, as it
        // would on a real bus; the sender's retry (a second copy) is then found.
        let mut second = Vec::new();
        encode(&mut second, id, instruction, &params);
        for _ in 0..(hand_control::protocol::MAX_LEN / second.len().max(1) + 2) {
            wire.extend_from_slice(&second);
        }
        let cut = split.index(wire.len());
        let mut p = Parser::default();
        let mut found = false;
        for part in [&wire[..cut], &wire[cut..]] {
            p.push(part);
            while let Some(r) = p.next_packet() {
                if let Ok(pkt) = r {
                    if pkt.id == id && pkt.instruction == instruction && pkt.params == params {
                        found = true;
                    }
                }
            }
        }
        prop_assert!(found, "packet after {} garbage bytes not found", tail);
    }
}

/// Instructions the simulator knows, plus a few it must refuse.
fn instruction() -> impl Strategy<Value = u8> {
    prop_oneof![
        prop::sample::select(vec![
            0x01u8, 0x02, 0x03, 0x04, 0x05, 0x06, 0x08, 0x10, 0x82, 0x83, 0x92, 0x93
        ]),
        any::<u8>().prop_filter("not the simulator's clock packet", |&i| i
            != hand_control::sim::CLOCK_INSTRUCTION),
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
        use hand_control::sim::{SimBus, SimConfig};
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
