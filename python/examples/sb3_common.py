"""What the SB3 examples share: SB3 PPO with a recipe's hyperparameters, the trained model as a
policy ``fairgrasp.evaluate`` and ``fairgrasp.compare`` take (held-out scenarios: the sets of
``fairgrasp eval --seed``, with Rust's 95 % Wilson intervals). A result's line is
``fairgrasp.compare.describe``. Nothing here imports SB3 or torch until a model is built."""

import os

try:
    import tomllib  # Python 3.11+
except ModuleNotFoundError:  # Python 3.10, the package's oldest: the same parser, from PyPI
    import tomli as tomllib

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def recipe_file(name):
    with open(os.path.join(ROOT, "assets", "experiments", name + ".toml"), "rb") as f:
        return tomllib.load(f)


def ppo_from_recipe(env, recipe, seed, zero_actor_output=None, **extra):
    """SB3 PPO with the recipe's [ppo] and [model]: separate tanh MLPs of `hidden` for actor and
    critic, `log_std_init`, the learning rate annealed linearly to 0 when `anneal_lr` (held until
    the fraction `anneal_from` of training, as `PpoConfig::learning_rate_at` does), the target
    KL, advantage normalisation; `norm_obs` is the caller's VecNormalize. With
    `zero_actor_output` the actor's output layer starts at zero (the untrained residual is the
    script); `actor_output_bias`, when given, is that layer's initial bias."""
    import torch
    from stable_baselines3 import PPO

    ppo, model = recipe["ppo"], recipe["model"]
    lr = ppo["learning_rate"]
    hold = ppo.get("anneal_from", 0.0)

    def anneal(left):  # SB3 passes the fraction of training left, from 1 to 0
        return lr * min(1.0, max(0.0, left / (1.0 - hold)))

    learning_rate = anneal if ppo.get("anneal_lr", False) else lr
    agent = PPO(
        "MlpPolicy",
        env,
        n_steps=ppo["n_steps"],
        batch_size=ppo["batch_size"],
        n_epochs=ppo["n_epochs"],
        gamma=ppo["gamma"],
        gae_lambda=ppo["gae_lambda"],
        clip_range=ppo["clip_coef"],
        ent_coef=ppo["ent_coef"],
        vf_coef=ppo["vf_coef"],
        max_grad_norm=ppo["max_grad_norm"],
        learning_rate=learning_rate,
        target_kl=ppo.get("target_kl"),
        normalize_advantage=ppo.get("norm_adv", True),
        policy_kwargs=dict(
            net_arch=dict(pi=model["hidden"], vf=model["hidden"]),
            activation_fn=torch.nn.Tanh,
            log_std_init=model["log_std_init"],
        ),
        seed=seed,
        device="cpu",
        **extra,
    )
    zero = model.get("zero_actor_output", False) if zero_actor_output is None else zero_actor_output
    bias = model.get("actor_output_bias", [])
    with torch.no_grad():
        if zero:
            agent.policy.action_net.weight.zero_()
            agent.policy.action_net.bias.zero_()
        if bias:
            agent.policy.action_net.bias.copy_(torch.tensor(bias, dtype=torch.float32))
    return agent


def policy_act(model, normalizer=None):
    """The SB3 model's deterministic action for one observation (through VecNormalize's
    statistics if given)."""

    def act(obs):
        x = obs if normalizer is None else normalizer.normalize_obs(obs[None, :])[0]
        action, _ = model.predict(x, deterministic=True)
        return np.asarray(action, dtype=np.float64)

    return act


