"""Which timing mechanism does your agent use? Fingerprint the example pacemaker agent
(``chronocooked.examples``) and a trained LSTM125 from the zoo.

    python examples/python/fingerprint_my_agent.py [OUT]     # default: lab-out/fingerprint

The lab's mechanisms protocol — fixed interval at TD 6 and TD 12, bisection 4-12, each
evaluated and recorded on probe trials — is played by your policies, and the agent's
signature is placed among the committed timing mechanisms (drift-diffusion, striatal beat
frequency, three kinds of time cells): its distance to each, beside the distances of that
mechanism's own unseen seeds. Writes OUT/pacemaker/ and OUT/lstm125/ (fingerprint.html,
fingerprint.png, fingerprint.json, one folder per condition); under a minute on 2 cores.
"""

import sys
from pathlib import Path

import chronocooked
from chronocooked.examples import make_pacemaker


def show(result):
    print(result["verdict"])
    for d in result["distances"]:
        lo, hi = d["self_range"] or (float("nan"), float("nan"))
        limit = float("nan") if d["limit"] is None else d["limit"]
        print(f"  {d['mechanism']:<18} distance {d['distance']:5.2f}   its own seeds "
              f"{lo:.2f}-{hi:.2f}   limit {limit:.2f}   bootstrap share "
              f"{d['bootstrap_share']:.2f}")
    if result["missing"]:
        print("  missing features:", ", ".join(result["missing"]))


def main(out):
    out = Path(out)
    # 1. Your agent: a factory of policies, one per condition. Its units are the same units
    #    at both TDs (one model), so the per-unit scaling is defined.
    show(chronocooked.fingerprint(make_pacemaker, out / "pacemaker", name="my-pacemaker",
                                  units_correspond=True, seed=0))
    # 2. A zoo agent: the zoo holds LSTM125 trained on fixed interval at TD 12 and on
    #    bisection 4-12, so the TD-6 condition is left out (its features are missing).
    zoo = {"fi-td12": chronocooked.zoo.load("lstm125/FixedInterval-v0"),
           "bisection-4-12": chronocooked.zoo.load("lstm125/Bisection-v0")}
    show(chronocooked.fingerprint(zoo, out / "lstm125", name="zoo-lstm125", draws=1, seed=0))
    print("cards:", out / "pacemaker" / "fingerprint.html", out / "lstm125" / "fingerprint.html")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "lab-out/fingerprint")
