//! The network tests as one test binary (one link step per area).

#[path = "../common/mod.rs"]
mod common;

mod cancel;
mod chain_patches;
mod continuation;
mod distributed;
mod expected;
mod invariants;
mod lookup;
mod one_answer;
mod output;
mod permutation;
mod round_scenes;
mod sparse;
mod stream;
mod stream_topology;
