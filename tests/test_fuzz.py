"""Property test of the case schema (issues 12 and 53): any bundled case with one field
mutated (deleted, a bad number, a wrong unit or type, an unknown neighbour, or one of issue
53's inputs past a formula's range) run through the command line gives exit 2 with one
line naming a field and nothing written, or a complete folder with a strict-JSON result of
physical figures and no library warning; never another exit code; issue 53's bad inputs
are refused and its legal ones answered; a mutated bundled sweep is planned or refused in
one line. A larger budget runs in benchmarks/fuzz.py."""

from hypothesis import HealthCheck, given, settings, strategies as st

import mutations

CASES = mutations.bundled()


@settings(max_examples=60, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(sorted(CASES)), rng=st.randoms(use_true_random=False))
def test_a_mutated_case_is_refused_cleanly_or_answered_completely(tmp_path_factory, name, rng):
    what, path, raw = mutations.mutate(mutations.small(CASES[name], interference=False), rng)
    folder = tmp_path_factory.mktemp("fuzz")
    case = mutations.write_case(raw, folder, "mutated", name)
    code, output = mutations.run_cli(case, folder / "out")
    problem = mutations.verdict(code, output, folder / "out")
    kind = mutations.classify(code, problem, what)
    assert kind is None, f"{name} {'.'.join(map(str, path))} ({what}): {kind}: {problem}"


SWEEPS = mutations.bundled_sweeps()


@settings(max_examples=20, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(sorted(SWEEPS)), rng=st.randoms(use_true_random=False))
def test_a_mutated_sweep_is_refused_in_one_line_or_planned(tmp_path_factory, name, rng):
    what, path, raw = mutations.mutate_sweep(SWEEPS[name], rng)
    code, output = mutations.plan_sweep(raw, tmp_path_factory.mktemp("sweep"), "mutated")
    assert code in (0, 2) and len(output.splitlines()) <= 1, f"{name} ({what}): {output}"
    assert mutations.classify(code, None, what) is None, f"{name} ({what}): {output}"
