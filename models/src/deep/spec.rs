//! The one parameter specification of an actor–critic network: every float parameter's
//! name and shape, in burn's visiting order. The native engine's [`ParamLayout`] is derived
//! from it (offsets are running sums of the shapes), checkpoints and the optimizer use the
//! same order (the flat vector of `params::flat_params`), and a native policy built from a
//! burn module is checked against it shape by shape ([`check_shapes`]).
//!
//! [`ParamLayout`]: crate::deep::native::ParamLayout

use crate::{CoreKind, PolicyConfig};

/// One float parameter: a dotted name and its shape (`[in, out]` for weights).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParamSpec {
    /// Dotted name (`trunk.conv1.weight`, `core.tau`, `head.pi.bias`, …).
    pub name: &'static str,
    /// Shape.
    pub shape: Vec<usize>,
}

impl ParamSpec {
    /// Number of elements.
    pub fn len(&self) -> usize {
        self.shape.iter().product()
    }

    /// Whether the parameter has no elements.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Every parameter of the network `cfg` builds, in burn's visiting order: trunk conv1
/// weight `[C, c1]` and bias, conv2 `[c1, c2]`, dense `[cells·c2, F]`; core input
/// `[F, G·H]` and bias, recurrent `[H, G·H]` (GRU: and bias), CTRNN `τ_raw [H]`; fused
/// head hidden layer `[L, 2·hh]`, policy output `[hh, A]`, value output `[hh, 1]`, each
/// weight followed by its bias (`G` gates, `L` = H with a core, F without).
pub fn param_spec(cfg: &PolicyConfig) -> Vec<ParamSpec> {
    let p = |name, shape: &[usize]| ParamSpec {
        name,
        shape: shape.to_vec(),
    };
    let t = &cfg.trunk;
    let mut v = vec![
        p("trunk.conv1.weight", &[t.channels, t.conv1]),
        p("trunk.conv1.bias", &[t.conv1]),
        p("trunk.conv2.weight", &[t.conv1, t.conv2]),
        p("trunk.conv2.bias", &[t.conv2]),
        p("trunk.dense.weight", &[t.cells * t.conv2, t.features]),
        p("trunk.dense.bias", &[t.features]),
    ];
    let mut latent = t.features;
    if let Some(kind) = cfg.arch.core {
        let (h, g) = (cfg.arch.hidden, kind.gates());
        v.push(p("core.input.weight", &[t.features, g * h]));
        v.push(p("core.input.bias", &[g * h]));
        v.push(p("core.recurrent.weight", &[h, g * h]));
        if kind == CoreKind::Gru {
            v.push(p("core.recurrent.bias", &[g * h]));
        }
        if kind == CoreKind::Ctrnn {
            v.push(p("core.tau", &[h]));
        }
        latent = h;
    }
    let hh = cfg.head_hidden;
    v.extend([
        p("head.hidden.weight", &[latent, 2 * hh]),
        p("head.hidden.bias", &[2 * hh]),
        p("head.pi.weight", &[hh, cfg.actions]),
        p("head.pi.bias", &[cfg.actions]),
        p("head.vf.weight", &[hh, 1]),
        p("head.vf.bias", &[1]),
    ]);
    v
}

/// Checks the shapes of a module's parameters (in visiting order) against `spec`, one by
/// one; the error names the first parameter that differs (or the count).
pub fn check_shapes(spec: &[ParamSpec], shapes: &[Vec<usize>]) -> Result<(), String> {
    for (k, (s, got)) in spec.iter().zip(shapes).enumerate() {
        if &s.shape != got {
            return Err(format!(
                "parameter {k} `{}`: the module has shape {got:?}, the specification {:?}",
                s.name, s.shape
            ));
        }
    }
    if spec.len() != shapes.len() {
        return Err(format!(
            "the module has {} parameters, the specification {}",
            shapes.len(),
            spec.len()
        ));
    }
    Ok(())
}
