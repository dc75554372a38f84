"""Stable-Baselines3 agents as lab policies, without glue code.

:func:`policy` turns a trained SB3 ``PPO`` (or any SB3 model with ``predict``) or an
sb3-contrib ``RecurrentPPO`` into a policy for :func:`chronocooked.evaluate` and
:func:`chronocooked.fingerprint`:

* observations are passed in the model's own space: the lab's code observation
  (``uint8 [R, C, 6]``) or the one-hot one (``float32 [channels, R, C]``), chosen from the
  model's ``observation_space`` (the policy's ``obs_mode`` attribute tells the lab which);
* episode starts follow RecurrentPPO's contract: the LSTM states are carried in the
  policy's state and reset by ``episode_start`` on an episode's first step;
* activity is recorded as named populations: ``features`` (the features extractor's
  output), ``latent_pi`` (the actor's MLP output) and, for RecurrentPPO, ``hidden`` and
  ``cell`` (the actor LSTM's hidden and cell states after the step, all layers).

SB3 stays optional: :func:`policy` only calls the model's own methods, and :func:`load`
imports SB3 when called, with a clear error saying what to install.
"""

from __future__ import annotations

import numpy as np

INSTALL = "pip install stable-baselines3 sb3-contrib"


def _require_sb3():
    try:
        import stable_baselines3  # noqa: F401
    except ImportError as err:
        raise ImportError(
            f"chronocooked.sb3 needs Stable-Baselines3 (and sb3-contrib for RecurrentPPO): {INSTALL}"
        ) from err


def _obs_mode(space) -> str:
    shape = tuple(getattr(space, "shape", ()) or ())
    if len(shape) == 3 and shape[2] == 6:
        return "codes"
    if len(shape) == 3:
        return "onehot"
    raise ValueError(
        f"the model's observation space {space} is neither the lab's code observation "
        "(uint8 [R, C, 6]) nor its one-hot one ([channels, R, C]): train it on a "
        "chronocooked env (gymnasium.make('chronocooked/<Task>'), obs_mode 'codes' or 'onehot')"
    )


class SB3Policy:
    """A trained SB3 model as a lab policy: ``policy(obs, state, episode_start) -> (action,
    state, activity)`` with ``activity`` a dict of named populations (see the module)."""

    def __init__(self, model, deterministic: bool = True, record: bool = True):
        self.model = model
        self.deterministic = deterministic
        self.obs_mode = _obs_mode(model.observation_space)
        self.dtype = model.observation_space.dtype
        self.recurrent = hasattr(model.policy, "lstm_actor")
        self._captured = {}
        self._hooks = []
        if record:
            self._hook("features", getattr(model.policy, "pi_features_extractor", None)
                       or getattr(model.policy, "features_extractor", None))
            mlp = getattr(model.policy, "mlp_extractor", None)
            self._hook("latent_pi", getattr(mlp, "policy_net", None))
        self.record = record

    def _hook(self, name, module):
        if module is None or not hasattr(module, "register_forward_hook"):
            return

        def keep(_module, _inputs, output):
            out = output[0] if isinstance(output, tuple) else output
            self._captured[name] = out.detach().cpu().numpy().reshape(-1).astype(np.float32)

        self._hooks.append(module.register_forward_hook(keep))

    def close(self):
        """Removes the recording hooks from the model."""
        for h in self._hooks:
            h.remove()
        self._hooks.clear()

    def __call__(self, obs, state, episode_start):
        x = np.asarray(obs, dtype=self.dtype)
        self._captured.clear()
        if self.recurrent:
            action, state = self.model.predict(
                x, state=state, episode_start=np.array([bool(episode_start)]),
                deterministic=self.deterministic)
        else:
            action, _ = self.model.predict(x, deterministic=self.deterministic)
            state = None
        action = int(np.asarray(action).reshape(-1)[0])
        if not self.record:
            return action, state
        activity = dict(self._captured)
        if self.recurrent:
            hidden, cell = state
            activity["hidden"] = np.asarray(hidden, dtype=np.float32).reshape(-1)
            activity["cell"] = np.asarray(cell, dtype=np.float32).reshape(-1)
        return action, state, activity


def policy(model, deterministic: bool = True, record: bool = True) -> SB3Policy:
    """A Stable-Baselines3 ``PPO`` or sb3-contrib ``RecurrentPPO`` model (anything with
    SB3's ``predict`` and a torch ``policy``) as a lab policy; ``record=False`` records no
    activity."""
    if not hasattr(model, "predict") or not hasattr(model, "policy"):
        raise TypeError(
            f"chronocooked.sb3.policy takes a Stable-Baselines3 model (PPO, RecurrentPPO, …), "
            f"got {type(model).__name__}")
    return SB3Policy(model, deterministic=deterministic, record=record)


def load(path, algo: str = "RecurrentPPO", deterministic: bool = True,
         record: bool = True) -> SB3Policy:
    """Loads a saved SB3 model (``model.save(path)``) of class ``algo`` (``"PPO"`` from
    stable-baselines3, ``"RecurrentPPO"`` from sb3-contrib) as a lab policy. SB3 is imported
    here; without it an ``ImportError`` says what to install."""
    _require_sb3()
    if algo == "RecurrentPPO":
        try:
            from sb3_contrib import RecurrentPPO as cls
        except ImportError as err:
            raise ImportError(f"RecurrentPPO needs sb3-contrib: {INSTALL}") from err
    elif algo == "PPO":
        from stable_baselines3 import PPO as cls
    else:
        raise ValueError(f"invalid value for `algo`: {algo!r} (allowed: 'PPO', 'RecurrentPPO')")
    return policy(cls.load(str(path), device="cpu"), deterministic=deterministic, record=record)
