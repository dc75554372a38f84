//! Flat views of a module's float parameters and their gradients, in the module's
//! (deterministic) visiting order: what the optimizer and checkpoints work on.

use burn::module::{Module, ModuleMapper, ModuleVisitor, Param};
use burn::tensor::{Gradients, Tensor, TensorData};

/// Reads a tensor into a `Vec<f32>` (row-major).
pub fn tensor_to_vec<const D: usize>(t: &Tensor<D>) -> Vec<f32> {
    chronocooked_models::to_vec(t)
}

struct Collect<'a> {
    grads: Option<&'a Gradients>,
    out: Vec<f32>,
}

impl ModuleVisitor for Collect<'_> {
    fn visit_float<const D: usize>(&mut self, param: &Param<Tensor<D>>) {
        let value = param.val();
        let n = value.shape().num_elements();
        match self.grads {
            None => self.out.extend(tensor_to_vec(&value)),
            Some(g) => match value.grad(g) {
                Some(grad) => self.out.extend(tensor_to_vec(&grad)),
                None => self.out.extend(std::iter::repeat_n(0.0, n)),
            },
        }
    }
}

/// All float parameters of `module`, concatenated.
pub fn flat_params<M: Module>(module: &M) -> Vec<f32> {
    let mut c = Collect {
        grads: None,
        out: Vec::new(),
    };
    module.visit(&mut c);
    c.out
}

struct Shapes(Vec<Vec<usize>>);

impl ModuleVisitor for Shapes {
    fn visit_float<const D: usize>(&mut self, param: &Param<Tensor<D>>) {
        self.0.push(param.val().dims().to_vec());
    }
}

/// The shape of every float parameter of `module`, in the order of [`flat_params`].
pub fn param_shapes<M: Module>(module: &M) -> Vec<Vec<usize>> {
    let mut s = Shapes(Vec::new());
    module.visit(&mut s);
    s.0
}

/// The gradients of all float parameters of `module` (zeros where a parameter got none),
/// in the same order as [`flat_params`].
pub fn flat_grads<M: Module>(module: &M, grads: &Gradients) -> Vec<f32> {
    let mut c = Collect {
        grads: Some(grads),
        out: Vec::new(),
    };
    module.visit(&mut c);
    c.out
}

struct Write<'a> {
    values: &'a [f32],
    offset: usize,
}

impl ModuleMapper for Write<'_> {
    fn map_float<const D: usize>(&mut self, param: Param<Tensor<D>>) -> Param<Tensor<D>> {
        param.map(|t| {
            let shape = t.shape();
            let n = shape.num_elements();
            let device = t.device();
            let require_grad = t.is_require_grad();
            let slice = self.values[self.offset..self.offset + n].to_vec();
            self.offset += n;
            let fresh: Tensor<D> = Tensor::from_data(TensorData::new(slice, shape), &device);
            if require_grad {
                fresh.require_grad()
            } else {
                fresh
            }
        })
    }
}

/// Replaces every float parameter of `module` by the matching slice of `values`
/// (layout of [`flat_params`]); parameter ids and gradient flags are kept.
///
/// # Panics
/// If `values` is shorter than the module's parameter count (a programming error).
pub fn write_params<M: Module>(module: M, values: &[f32]) -> M {
    let mut w = Write { values, offset: 0 };
    let m = module.map(&mut w);
    assert_eq!(w.offset, values.len(), "parameter vector length mismatch");
    m
}

struct Offset {
    target: burn::module::ParamId,
    offset: usize,
    found: Option<usize>,
}

impl ModuleVisitor for Offset {
    fn visit_float<const D: usize>(&mut self, param: &Param<Tensor<D>>) {
        if param.id == self.target {
            self.found = Some(self.offset);
        }
        self.offset += param.shape().num_elements();
    }
}

/// Offset of parameter `id` in the [`flat_params`] layout.
pub fn param_offset<M: Module>(module: &M, id: burn::module::ParamId) -> Option<usize> {
    let mut o = Offset {
        target: id,
        offset: 0,
        found: None,
    };
    module.visit(&mut o);
    o.found
}

struct StableIds(u64);

impl ModuleMapper for StableIds {
    fn map_float<const D: usize>(&mut self, mut param: Param<Tensor<D>>) -> Param<Tensor<D>> {
        param.id = burn::module::ParamId::from(self.0);
        self.0 += 1;
        param
    }
}

/// `module` with its float parameters numbered 0, 1, … in visiting order instead of burn's
/// random parameter ids, so a saved model (`model.bpk`) is a function of the weights alone:
/// the same training gives the same bytes.
pub fn with_stable_ids<M: Module>(module: M) -> M {
    module.map(&mut StableIds(0))
}
