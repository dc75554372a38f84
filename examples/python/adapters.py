"""Adapters from common Python agents to the policy callable of `chronocooked.evaluate`:
``policy(obs, state, episode_start) -> (action, state[, activity])``.

Not required dependencies of the package: import what you use.
"""

import numpy as np


def sb3_policy(model, deterministic=True):
    """A Stable-Baselines3 ``PPO`` (or any model with ``predict``) as a policy. For
    sb3-contrib ``RecurrentPPO`` the LSTM state is threaded through ``state`` and the hidden
    state is returned as the activity (``[hidden]`` of the actor LSTM's output state)."""
    recurrent = hasattr(model.policy, "lstm_actor")

    def policy(obs, state, episode_start):
        if recurrent:
            action, state = model.predict(obs[None], state=state,
                                          episode_start=np.array([episode_start]),
                                          deterministic=deterministic)
            hidden = np.asarray(state[0]).reshape(-1)  # (layers, 1, H) -> [H]
            return int(action[0]), state, hidden.astype(np.float32)
        action, _ = model.predict(obs, deterministic=deterministic)
        return int(action), None

    return policy


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
