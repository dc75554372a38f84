"""Adapters from common Python agents to the policy callable of `chronocooked.evaluate`:
``policy(obs, state, episode_start) -> (action, state[, activity])``. Stable-Baselines3
models have theirs in the package: ``chronocooked.sb3.policy(model)``.

Not required dependencies of the package: import what you use.
"""

import numpy as np


def torch_policy(module, recurrent=False):
    """A ``torch.nn.Module`` mapping a batch of observations (and, if ``recurrent``, a hidden
    state) to action logits as a greedy policy: ``module(obs[None])`` -> logits, or
    ``module(obs[None], h)`` -> (logits, h). The hidden state is returned as the activity."""
    import torch

    @torch.no_grad()
    def policy(obs, state, episode_start):
        x = torch.as_tensor(np.asarray(obs, dtype=np.float32))[None]
        if recurrent:
            h = None if episode_start else state
            logits, h = module(x, h)
            act = h[0] if isinstance(h, tuple) else h
            return int(logits.argmax(-1)[0]), h, act.reshape(-1).numpy().astype(np.float32)
        return int(module(x).argmax(-1)[0]), None

    return policy
