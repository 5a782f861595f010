"""Ray RLlib PPO (the new API stack) on the task-space residual env of the preset's task (the
recipe `--recipe`, default the preset's residual recipe: `residual_miscalibrated` on a lift preset,
the place task's on a place preset), on the native vector env:
RLlib's env runner builds `FairGrasp-Residual-<Preset>-v0` with
`gym_env_vectorize_mode="vector_entry_point"`, so the 8 envs step on Rust threads
(`fairgrasp.VectorEnv`) instead of RLlib's Python loop over 8 single envs. The
`residual_miscalibrated` recipe's hyperparameters as far as RLlib has them (8 × 128 samples per
update, minibatches of 256, 8 epochs, γ 0.98, λ 0.95, clip 0.2, lr 3e-4 annealed to 0, tanh MLPs
of 64 × 64 for actor and critic, the actor's output layer zeroed so the untrained policy is the
script, log σ −1.2, observations normalised by a running mean and std); RLlib has no target-KL
early stop (its KL penalty is off here) and no critic warm-up. At the end `fairgrasp.compare`
plays the trained policy beside the scripts on `--episodes` held-out scenarios (the set of
`fairgrasp eval --seed EVAL_SEED`; training's scenario seeds are 100 000 000 + seed + i·10⁶ + k,
never those), with 95 % Wilson intervals and McNemar's paired test, into the report folder `--out`.

    scripts/rllib-venv.sh
    nice -n 10 target/rllib-venv/bin/python python/examples/rllib_ppo.py --preset nudged --timesteps 300000 --out runs/rllib_residual_nudged_s0

One process: the env runner and the learner run in the driver (`num_env_runners=0`,
`num_learners=0`), as SB3 does, so the throughput compares. On a Ray cluster (`ray start --head`,
`ray start --address=HEAD:6379`, fairgrasp installed on every node), `--address auto
--runners N` samples on N remote env runners instead. Needs torch and Ray RLlib (the venv
above); not part of CI (its reporting step, `report`, is tested with a stub policy in
python/tests/test_examples.py).
"""

import json
import os
import time

import gymnasium as gym
import numpy as np

import fairgrasp
from report_step import compare_with_scripts, residual_parser, with_recipe

NAME = "RLlib PPO residual"


def parse_args(argv=None):
    parser = residual_parser("runs/rllib_residual_report")
    parser.add_argument("--envs", type=int, default=8, help="envs of the native vector env (per env runner)")
    parser.add_argument("--threads", type=int, default=2, help="Rust threads of the vector env")
    parser.add_argument("--runners", type=int, default=0, help="remote env runners (0: sample in this process)")
    parser.add_argument("--address", default=None, help="an existing Ray cluster (e.g. auto)")
    parser.add_argument("--log", default=None, help="append one JSON line per training iteration and the result")
    args = parser.parse_args(argv)
    if not 0 <= args.seed < 1_000_000:
        parser.error(f"--seed {args.seed}: must be in 0–999999 (training scenario seeds start at 100 000 000 + seed)")
    if args.timesteps < 1 or args.episodes < 1 or args.envs < 1 or args.threads < 1:
        parser.error("--timesteps, --episodes, --envs and --threads must be positive")
    return with_recipe(args)


def log(args, row):
    print(json.dumps(row), flush=True)
    if args.log:
        with open(args.log, "a") as f:
            f.write(json.dumps(row) + "\n")


def report(act, args, steps, train_s):
    """The reporting step: the trained policy ``act`` (``obs -> action`` on the recipe's env) in
    the report folder ``args.out`` beside the task's scripts; prints the result against the
    open-loop script and logs it as one JSON row, which it returns."""
    pair = compare_with_scripts(NAME, act, recipe=args.recipe, preset=args.preset, episodes=args.episodes,
                                eval_seed=args.eval_seed, out=args.out, force=args.force, shipped=True)
    trained, script = pair["method"], pair["script"]
    row = {"recipe": args.recipe, "preset": args.preset, "seed": args.seed, "timesteps": steps,
           "train_wall_s": round(train_s, 1), "steps_per_s": round(steps / train_s, 1) if train_s > 0 else None,
           "episodes": args.episodes, "eval_seed": args.eval_seed,
           "trained": trained["successes"], "ci95": [trained["ci_low"], trained["ci_high"]],
           "trained_outcomes": trained["outcomes"], "script_name": script["method"], "script": script["successes"],
           "difference_points": pair["difference_points"], "report": args.out}
    log(args, row)
    return row


def read_recipe(name):
    """The recipe ``name`` of ``assets/experiments/`` as a dict."""
    try:
        import tomllib  # Python 3.11+
    except ModuleNotFoundError:  # Python 3.10, the package's oldest: the same parser, from PyPI
        import tomli as tomllib

    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    with open(os.path.join(root, "assets", "experiments", name + ".toml"), "rb") as f:
        return tomllib.load(f)


class NextStepAutoreset(gym.vector.VectorWrapper):
    """fairgrasp.VectorEnv for RLlib's single-agent env runner. The native vector env resets an
    ended episode in the same step (the observation returned is the next episode's first, the
    ended one's last is in info["final_obs"]); RLlib 2.60 expects gymnasium's default, the reset
    one step later (it records the observation of the step after an ending as the new
    episode's first and ignores that step's action and reward). So: on the step an episode
    ends, hand RLlib the ended episode's last observation and its info; on the next step, play
    that sub-env's new episode one step with a zero correction (the script's own action) and
    hand RLlib the observation after it as the new episode's first. RLlib thus sees each
    episode from its second step; the first step of every episode is the script's."""

    KEYS = ("success", "step", "simulated", "scenario_seed")

    def __init__(self, env):
        super().__init__(env)
        self.metadata = {**env.metadata, "autoreset_mode": gym.vector.AutoresetMode.NEXT_STEP}
        self._pending = np.zeros(env.num_envs, dtype=bool)

    def _flat(self, info):
        return {k: np.array(info[k]) for k in self.KEYS + tuple("_" + k for k in self.KEYS) if k in info}

    def reset(self, *, seed=None, options=None):
        obs, info = self.env.reset(seed=seed, options=options)
        self._pending[:] = False
        return obs, self._flat(info)

    def step(self, actions):
        actions = np.array(actions, dtype=np.float64)
        actions[self._pending] = 0.0
        # The native env's own step: VectorEnv.step batches the ended episodes' infos with
        # gymnasium's _add_info, which raises AttributeError when two episodes end in one step
        # and one has `failure: None`, the other a failure dict; only these flat keys are needed.
        obs, rewards, terminated, truncated, info, ended = self.env._native.step(actions)
        flat = {k: np.array(info[k]) for k in self.KEYS if k in info}
        done = np.zeros(self.num_envs, dtype=bool)
        for i, last, last_info in ended:
            if self._pending[i]:
                continue  # a new episode that ended on its very first step (never seen here): lost to RLlib
            done[i] = True
            obs[i] = last
            for k in flat:
                if k in last_info:
                    flat[k][i] = last_info[k]
        for k in list(flat):
            flat["_" + k] = np.ones(self.num_envs, dtype=bool)
        self._pending = done
        return obs, rewards, terminated, truncated, flat


def make_env(cfg):
    return NextStepAutoreset(fairgrasp.VectorEnv(num_envs=cfg["num_envs"], recipe=cfg["recipe"],
                                                 preset=cfg["preset"], threads=cfg["threads"]))


def record_success(episode, metrics_logger, **kwargs):
    """Training success over the last 200 episodes (RLlib's metrics), for the progress lines."""
    metrics_logger.log_value("success", float(episode.get_infos(-1)["success"]), window=200)


def build_algo(args, recipe):
    """RLlib's PPO on the recipe's env with its hyperparameters (see the module doc), the actor's
    output layer zeroed when the recipe's model says so."""
    import torch
    from ray.rllib.algorithms.ppo import PPOConfig
    from ray.rllib.connectors.env_to_module import MeanStdFilter
    from ray.rllib.core.rl_module.default_model_config import DefaultModelConfig
    from ray.tune.registry import register_env

    ppo, model = recipe["ppo"], recipe["model"]
    register_env("fairgrasp_residual", make_env)
    # RLlib resets the env runner's envs once with config.seed (+ the runner's index): the native
    # vector env then plays scenario seeds from there. 100 000 000 + seed keeps them far from the
    # held-out sets (set 7 is 7 000 021 + i) and below 2³² (RLlib also seeds NumPy with it).
    train_seed = 100_000_000 + args.seed
    config = (
        PPOConfig()
        .environment("fairgrasp_residual", env_config={"recipe": args.recipe, "preset": args.preset,
                                                       "threads": args.threads},
                     clip_actions=True)
        .env_runners(
            num_env_runners=args.runners,
            num_envs_per_env_runner=args.envs,
            gym_env_vectorize_mode="vector_entry_point",
            rollout_fragment_length=ppo["n_steps"],
            env_to_module_connector=lambda env, spaces, device: MeanStdFilter(clip_by_value=10.0),
        )
        .learners(num_learners=0)
        .training(
            train_batch_size_per_learner=args.envs * ppo["n_steps"],
            minibatch_size=ppo["batch_size"],
            num_epochs=ppo["n_epochs"],
            gamma=ppo["gamma"],
            lambda_=ppo["gae_lambda"],
            clip_param=ppo["clip_coef"],
            vf_clip_param=1e9,  # the recipe does not clip the value loss (clip_vloss = false)
            entropy_coeff=ppo["ent_coef"],
            vf_loss_coeff=ppo["vf_coef"],
            grad_clip=ppo["max_grad_norm"],
            grad_clip_by="global_norm",
            use_kl_loss=False,
            # Annealed linearly to 0 over the run, as anneal_lr does in the Rust trainer and SB3.
            lr=[[0, ppo["learning_rate"]], [args.timesteps, 0.0]] if ppo.get("anneal_lr") else ppo["learning_rate"],
        )
        .rl_module(model_config=DefaultModelConfig(fcnet_hiddens=model["hidden"], fcnet_activation="tanh",
                                                   head_fcnet_hiddens=[], vf_share_layers=False))
        .callbacks(on_episode_end=record_success)
        .debugging(seed=train_seed)
    )
    algo = config.build_algo()

    def zero_actor_output(learner):
        """The actor's last layer: means 0 (the script) and log σ the recipe's log_std_init."""
        module = learner.module["default_policy"]
        layer = [m for m in module.pi.modules() if isinstance(m, torch.nn.Linear)][-1]
        act_dim = layer.out_features // 2
        with torch.no_grad():
            layer.weight.zero_()
            layer.bias[:act_dim] = 0.0
            layer.bias[act_dim:] = model["log_std_init"]
        return act_dim

    if model.get("zero_actor_output", False):
        algo.learner_group.foreach_learner(zero_actor_output)
        algo.env_runner_group.sync_weights(from_worker_or_learner_group=algo.learner_group, inference_only=True)
    return algo


def train(algo, args):
    """Trains until ``args.timesteps`` env steps: ``(steps, wall seconds)``."""
    start, steps, iteration = time.time(), 0, 0
    while steps < args.timesteps:
        result = algo.train()
        iteration += 1
        steps = int(result["num_env_steps_sampled_lifetime"])
        runners = result.get("env_runners", {})
        if iteration % 10 == 0 or steps >= args.timesteps:
            wall = time.time() - start
            log(args, {"iteration": iteration, "steps": steps, "wall_s": round(wall, 1),
                       "steps_per_s": round(steps / wall, 1),
                       "episode_return_mean": runners.get("episode_return_mean"),
                       "episode_len_mean": runners.get("episode_len_mean"),
                       "training_success_last_200": runners.get("success")})
    return steps, time.time() - start


def trained_policy(algo):
    """The trained policy outside RLlib: the env runner's observation filter (frozen) and the
    module's deterministic action (the Gaussian's mean, clipped to the action space)."""
    import torch
    from ray.rllib.connectors.env_to_module import MeanStdFilter

    filters = [c for c in algo.env_runner._env_to_module.connectors if isinstance(c, MeanStdFilter)]
    obs_filter = next(iter(filters[0]._filters.values()))
    module = algo.get_module()

    def act(obs):
        x = obs_filter(np.asarray(obs, dtype=np.float32)[None, :], update=False)
        with torch.no_grad():
            out = module.forward_inference({"obs": torch.as_tensor(np.asarray(x, dtype=np.float32))})
        mean = out["action_dist_inputs"][0, : out["action_dist_inputs"].shape[1] // 2].numpy()
        return np.clip(mean.astype(np.float64), -1.0, 1.0)

    return act


def main(argv=None):
    args = parse_args(argv)
    import ray  # after the argument checks: importing Ray takes seconds

    ray.init(address=args.address, include_dashboard=False, num_cpus=None if args.address else 2,
             log_to_driver=False)
    algo = build_algo(args, read_recipe(args.recipe))
    steps, train_s = train(algo, args)
    report(trained_policy(algo), args, steps, train_s)
    ray.shutdown()


if __name__ == "__main__":
    main()
