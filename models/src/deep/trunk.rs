//! The paper's CNN trunk: Conv1×1 C→8, ReLU, Conv1×1 8→6, flatten, Linear→64, ReLU
//! (no non-linearity between the second conv and the flatten, as in the paper's `CustomCNN`).
//!
//! A 1×1 convolution is the same linear map applied at every grid cell, so it is
//! computed as a dense layer over the channel axis of `[B, cells, C]` (identical
//! function, cheaper on CPU). Flattening is cell-major (`[B, cells·6]`), a fixed
//! permutation of PyTorch's channel-major flatten — the same function class.

use crate::deep::init::{InitRng, linear_orthogonal};
use burn::module::Module;
use burn::nn::Linear;
use burn::tensor::Device;
use burn::tensor::Tensor;
use burn::tensor::activation::relu;
use serde::{Deserialize, Serialize};

/// Shape of the trunk.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TrunkConfig {
    /// Grid cells `R·C` (FI layout: 15).
    pub cells: usize,
    /// Input channels per cell (6 codes, or the one-hot channel count).
    pub channels: usize,
    /// Channels after the first 1×1 conv (reference 8).
    pub conv1: usize,
    /// Channels after the second 1×1 conv (reference 6).
    pub conv2: usize,
    /// Output features (reference 64).
    pub features: usize,
}

impl TrunkConfig {
    /// The reference trunk for a grid of `cells` cells with `channels` input channels.
    pub fn reference(cells: usize, channels: usize) -> Self {
        TrunkConfig {
            cells,
            channels,
            conv1: 8,
            conv2: 6,
            features: 64,
        }
    }

    /// Orthogonal init with gain √2 (SB3's feature-extractor init), zero biases.
    pub fn init(&self, rng: &mut InitRng, device: &Device) -> Trunk {
        let g = std::f64::consts::SQRT_2;
        Trunk {
            conv1: linear_orthogonal(self.channels, self.conv1, g, rng, device),
            conv2: linear_orthogonal(self.conv1, self.conv2, g, rng, device),
            dense: linear_orthogonal(self.cells * self.conv2, self.features, g, rng, device),
            cells: self.cells,
        }
    }
}

/// CNN trunk module (see the module docs).
#[derive(Module, Debug)]
pub struct Trunk {
    /// 1×1 conv C→8 as a per-cell dense layer.
    pub conv1: Linear,
    /// 1×1 conv 8→6 as a per-cell dense layer.
    pub conv2: Linear,
    /// Flattened `cells·6 → 64`.
    pub dense: Linear,
    /// Grid cells.
    #[module(skip)]
    pub cells: usize,
}

impl Trunk {
    /// `obs [B, cells, C]` → features `[B, 64]`.
    pub fn forward(&self, obs: Tensor<3>) -> Tensor<2> {
        let [b, cells, _] = obs.dims();
        let x = relu(self.conv1.forward(obs));
        let x = self.conv2.forward(x);
        let x: Tensor<2> = x.reshape([b, cells * self.conv2.weight.dims()[1]]);
        relu(self.dense.forward(x))
    }
}
