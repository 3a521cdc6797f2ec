#!/usr/bin/env python3
"""Times the reference engine in scikit-fuzzy 0.5.0 and pyfuzzylite 8.0.6.

The engine: e, de on [-1, 1] with 9 terms each (centres -1, -0.75 ... 1; NH / PH Gaussian
sigma 0.1667, the rest triangles of half-width 0.25), output tau on [-1, 1] with 9 Gaussians
sigma 0.125, 81 rules `e is T_i and de is T_j -> tau is T_clamp(i+j-4)`, min / max / min,
centroid over 201 samples. Prints JSON: microseconds per evaluation per peer.
"""
import json
import time

import numpy as np

NAMES = ["NH", "NB", "NM", "NS", "ZO", "PS", "PM", "PB", "PH"]
CENTRES = [-1 + 0.25 * i for i in range(9)]


def inputs(n):
    # The same deterministic sweep as benches/fuzzy_eval.rs.
    return [(-1.05 + 2.1 * ((k * 0.618034) % 1.0), -1.05 + 2.1 * ((k * 0.414214) % 1.0)) for k in range(n)]


def skfuzzy_peer():
    import skfuzzy as fuzz
    from skfuzzy import control as ctrl
    u = np.linspace(-1, 1, 201)
    e, de, tau = ctrl.Antecedent(u, "e"), ctrl.Antecedent(u, "de"), ctrl.Consequent(u, "tau")
    for i, (n, c) in enumerate(zip(NAMES, CENTRES)):
        for v in (e, de):
            v[n] = fuzz.gaussmf(u, c, 0.1667) if i in (0, 8) else fuzz.trimf(u, [c - 0.25, c, c + 0.25])
        tau[n] = fuzz.gaussmf(u, c, 0.125)
    rules = [ctrl.Rule(e[NAMES[i]] & de[NAMES[j]], tau[NAMES[min(max(i + j - 4, 0), 8)]])
             for i in range(9) for j in range(9)]
    sim = ctrl.ControlSystemSimulation(ctrl.ControlSystem(rules))

    def run(x):
        sim.input["e"], sim.input["de"] = min(max(x[0], -1), 1), min(max(x[1], -1), 1)
        sim.compute()
        return sim.output["tau"]
    return run


def fuzzylite_peer():
    import fuzzylite as fl
    def terms():
        return [fl.Gaussian(n, c, 0.1667) if i in (0, 8) else fl.Triangle(n, c - 0.25, c, c + 0.25)
                for i, (n, c) in enumerate(zip(NAMES, CENTRES))]
    engine = fl.Engine(
        name="reference",
        input_variables=[fl.InputVariable("e", -1, 1, lock_range=True, terms=terms()),
                         fl.InputVariable("de", -1, 1, lock_range=True, terms=terms())],
        output_variables=[fl.OutputVariable("tau", -1, 1, aggregation=fl.Maximum(),
                                            defuzzifier=fl.Centroid(201),
                                            terms=[fl.Gaussian(n, c, 0.125) for n, c in zip(NAMES, CENTRES)])],
        rule_blocks=[fl.RuleBlock(conjunction=fl.Minimum(), implication=fl.Minimum(), activation=fl.General(), rules=[
            fl.Rule.create(f"if e is {NAMES[i]} and de is {NAMES[j]} then tau is {NAMES[min(max(i + j - 4, 0), 8)]}")
            for i in range(9) for j in range(9)])],
    )
    e, de, tau = engine.input_variable("e"), engine.input_variable("de"), engine.output_variable("tau")

    def run(x):
        e.value, de.value = x
        engine.process()
        return tau.value
    return run


def time_us(run, n):
    xs = inputs(n)
    run(xs[0])  # warm-up
    start = time.perf_counter()
    for x in xs:
        run(x)
    return (time.perf_counter() - start) / n * 1e6


def main():
    print(json.dumps({
        "scikit-fuzzy": round(time_us(skfuzzy_peer(), 20), 1),
        "pyfuzzylite": round(time_us(fuzzylite_peer(), 200), 1),
    }))


if __name__ == "__main__":
    main()
