"""Property test of the case schema (issue 12): any bundled case with one field mutated
(deleted, a bad number, a wrong unit or type, an unknown neighbour) run through the
command line gives exit 2 with one line naming a field and nothing written, or a complete
folder with a strict-JSON result; never another exit code. A larger budget runs in
benchmarks/fuzz.py."""

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
    assert problem is None, f"{name} {'.'.join(map(str, path))} ({what}): {problem}"
