//! The deep-RL models of the paper as burn modules, and their native (hand-derived
//! forward/backward) twin used for fast training:
//!
//! * [`trunk`] — the paper's CNN feature extractor (1×1 convs + linear, 64 features);
//! * [`cores`] — recurrent cores: LSTM, GRU, vanilla RNN, CTRNN (Euler, learnable τ);
//! * [`policy`] — actor–critic heads over trunk (+ core): CNN-MLP, CNN-LSTM, CNN-CTRNN …;
//! * [`init`] — initialisers (orthogonal, PyTorch defaults);
//! * [`spec`] — the one parameter specification (names, shapes, order) both engines use;
//! * [`native`] — the same networks on a flat parameter vector (AVX2 kernels, BPTT).

pub mod cores;
pub mod init;
pub mod native;
pub mod policy;
pub mod spec;
pub mod trunk;
