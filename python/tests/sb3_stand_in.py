"""A pure-numpy stand-in for a trained Stable-Baselines3 model, with SB3's contract: an
``observation_space``, ``predict(obs, state, episode_start, deterministic)`` returning
``(action, state)`` (RecurrentPPO: ``state`` = ``(hidden, cell)``, each ``[layers, envs,
H]``, zeroed where ``episode_start``), and a ``policy`` whose ``features_extractor`` and
``mlp_extractor.policy_net`` are modules with ``register_forward_hook``. Lets CI test the
adapter's logic without torch; the real classes are tested where SB3 is installed."""

import gymnasium as gym
import numpy as np

import chronocooked  # noqa: F401  (registers the envs)


class _Tensor:
    """What a torch module returns, as far as the hooks read it."""

    def __init__(self, a):
        self.a = np.asarray(a, dtype=np.float32)

    def detach(self):
        return self

    def cpu(self):
        return self

    def numpy(self):
        return self.a


class _Handle:
    def __init__(self, hooks, fn):
        self.hooks, self.fn = hooks, fn

    def remove(self):
        self.hooks.remove(self.fn)


class _Module:
    """A module computing ``fn(x)`` and calling its forward hooks, as torch does."""

    def __init__(self, fn):
        self.fn, self.hooks = fn, []

    def register_forward_hook(self, hook):
        self.hooks.append(hook)
        return _Handle(self.hooks, hook)

    def __call__(self, x):
        out = _Tensor(self.fn(x))
        for h in list(self.hooks):
            h(self, (x,), out)
        return out


class _Policy:
    pass


class StandInModel:
    """``recurrent``: an LSTM-like state whose cell counts the steps since the episode
    start (``cell = previous cell · (1 − episode_start) + 1``) and whose hidden state is
    ``tanh`` of the features plus half the previous hidden. Features: the first 4 codes of
    the agent's cell channel, flattened. Actions: WAIT, except INTERACT every 5th step."""

    H = 3

    def __init__(self, obs_shape=None, recurrent=True):
        if obs_shape is None:  # the fixed-interval kitchen's code observation
            obs_shape = gym.make("chronocooked/FixedInterval-v0").observation_space.shape
        self.observation_space = gym.spaces.Box(0, 255, obs_shape, dtype=np.uint8)
        self.policy = _Policy()
        self.policy.features_extractor = _Module(
            lambda x: np.asarray(x, dtype=np.float32).reshape(-1)[:4] / 10.0)
        self.policy.mlp_extractor = _Policy()
        self.policy.mlp_extractor.policy_net = _Module(lambda f: np.tanh(f.a[:2]))
        if recurrent:
            self.policy.lstm_actor = object()
        self.recurrent = recurrent
        self.calls = []

    def predict(self, obs, state=None, episode_start=None, deterministic=False):
        assert obs.shape == self.observation_space.shape and obs.dtype == np.uint8
        self.calls.append(deterministic)
        features = self.policy.features_extractor(obs)
        self.policy.mlp_extractor.policy_net(features)
        if not self.recurrent:
            return np.array(0), None
        if state is None:
            state = (np.zeros((1, 1, self.H)), np.zeros((1, 1, self.H)))
        keep = 1.0 - np.asarray(episode_start, dtype=float).reshape(1, -1, 1)
        hidden, cell = state[0] * keep, state[1] * keep
        cell = cell + 1.0
        hidden = np.tanh(features.a[: self.H].reshape(1, 1, -1) + 0.5 * hidden)
        action = 5 if int(cell[0, 0, 0]) % 5 == 0 else 0
        return np.array([action]), (hidden, cell)
