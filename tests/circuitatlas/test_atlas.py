"""The circuit atlas: patterns, the rank filter, universality proofs and refutations, the search."""

from __future__ import annotations

import itertools
import json
import random
import subprocess
import sys

import control
import numpy as np
import pytest
import sympy as sp
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

import symctl
from symctl import NotRealizableError, ParameterError, SymctlTypeError, z
from symctl.circuitatlas.certify import certified_real_root
from symctl.circuitatlas.fibre import solve_at
from symctl.circuitatlas.pattern import Pattern, canonical_mask, slot_names
from symctl.circuitatlas.rank import generic_rank
from symctl.circuitatlas.search import canonical_masks
from symctl.circuitatlas.universality import decide, sample_targets


@pytest.fixture(scope="module")
def atlas2():
    return symctl.atlas(2, workers=1)


def _symbolic_rank(p: Pattern) -> int:
    """The rank of the Jacobian of (a, c) in the pattern's entries, over Q(entries): SymPy."""
    syms = p.symbols()
    F, H, M = p.matrices(syms)
    n = p.n
    A = z * sp.eye(n) - F
    a = sp.Poly(A.det(), z).all_coeffs()[1:]
    b = sp.Poly(sp.expand((M * A.adjugate() * H)[0]), z).all_coeffs()
    coeffs = [*a, *b]
    J = sp.Matrix([[sp.diff(f, s) for s in syms.values()] for f in coeffs])
    return J.rank() if syms else 0


@settings(max_examples=examples(40), deadline=None)
@given(st.integers(min_value=0, max_value=2**8 - 1))
def test_generic_rank_mod_p_equals_the_symbolic_jacobian_rank_at_order_2(mask):
    p = Pattern(2, mask)
    rank = generic_rank(p)
    if rank.minimal:  # below minimality the coefficient count is the same, the rank is too
        assert rank.rank == _symbolic_rank(p)


def test_canonical_masks_give_one_pattern_per_permutation_orbit():
    for n in (2, 3):
        slots = n * n + 2 * n
        for size in (n, 2 * n, 3 * n):
            combos = itertools.combinations(range(slots), size)
            brute = {canonical_mask(n, sum(1 << k for k in c)) for c in combos}
            assert sorted(brute) == sorted(canonical_masks(n, size))


def test_patterns_are_values_with_permutation_orbits():
    p = Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1])
    assert p == Pattern(2, p.mask) and hash(p) == hash(Pattern(2, p.mask))
    assert p.permuted((1, 0)) in p.orbit() and len(p.orbit()) == 2
    assert p.canonical() == p.permuted((1, 0)).canonical()
    assert slot_names(2)[:2] == ("F[1,1]", "F[1,2]")


def test_order_2_atlas_has_nine_universal_classes_and_the_papers_three_among_them(atlas2):
    from symctl.report.atlas import paper_realizations

    assert len(atlas2.universal_classes) == 9
    assert atlas2.stats["complete"] and atlas2.stats["undecided"] == 0
    ours = paper_realizations(atlas2)
    assert ours["controllable canonical"].label == "A1"  # the sparsest: 2 neurons
    assert ours["controllable canonical"].n_neurons == 2
    assert ours["observable canonical"].n_neurons == 3
    assert ours["general"].representatives[0].size == 8
    assert all(c.universal and c.evidence.proved for c in ours.values())


def test_sparsest_class_is_first_and_classes_are_ranked_by_neurons_then_synapses(atlas2):
    ranked = [(c.n_neurons, c.n_synapses) for c in atlas2.universal_classes]
    assert ranked == sorted(ranked)
    assert atlas2.sparsest() is atlas2.classes[0]


@pytest.mark.parametrize("region", ["1 complex pair", "real poles +-"])
def test_every_universal_order_2_class_realizes_sampled_controllers_exactly(atlas2, region):
    rng = random.Random(7)
    targets = [t for t in sample_targets(2, rng, per_region=2) if t[0] == region]
    for _, a, c in targets:
        G2 = 3 + (c[0] + c[1] * z) / (z**2 + a[1] * z + a[0])
        for cls in atlas2.universal_classes:
            R = cls.realize(G2)
            assert Pattern.of(R).canonical() == cls.representatives[0]
            if R.params["method"] == "closed form":
                assert symctl.check_realization(R, G2, "exact")
            else:  # algebraic entries: proved inside realize; cross-check in floats
                Rn = [np.array(m.evalf(30), dtype=float) for m in (R.F, R.H, R.M, R.N)]
                sys = control.ss(*Rn, True)
                zz = np.exp(0.7j)
                assert abs(sys(zz) - complex(G2.subs(z, zz))) < 1e-9


def test_realization_agrees_with_python_control(atlas2):
    G2 = 2 + (z - sp.Rational(1, 3)) / (z**2 - z / 2 + sp.Rational(1, 4))
    R = atlas2.classes[0].realize(G2)
    sys = control.ss(*(np.array(m, dtype=float) for m in (R.F, R.H, R.M, R.N)), True)
    for w in (0.3, 1.1, 2.5):
        zz = np.exp(1j * w)
        want = complex(G2.subs(z, zz))
        assert abs(sys(zz) - want) < 1e-12 * (1 + abs(want))


def test_closed_form_class_realizes_a_symbolic_G2(atlas2):
    a0, a1, c0, c1 = sp.symbols("a0 a1 c0 c1")
    G2 = 5 + (c1 * z + c0) / (z**2 + a1 * z + a0)
    R = atlas2.classes[0].realize(G2)
    assert R.params["method"] == "closed form"
    assert symctl.check_realization(R, G2, "exact")


def test_triangular_F_is_refuted_and_cannot_realize_complex_poles(atlas2):
    tri = Pattern.from_matrices([[1, 1], [0, 1]], [1, 1], [1, 1])
    ev = decide(tri)
    assert ev.universal is False and ev.method == "real eigenvalues" and ev.proved
    cls = atlas2.find(tri)
    with pytest.raises(NotRealizableError, match="not realizable"):
        cls.realize(1 + (z + 1) / (z**2 + 1))
    R = cls.realize(1 + (z + 1) / ((z - sp.Rational(1, 2)) * (z + sp.Rational(1, 3))))
    assert symctl.check_realization(
        R, 1 + (z + 1) / ((z - sp.Rational(1, 2)) * (z + sp.Rational(1, 3)))
    )


def test_a_counterexample_has_no_real_realization_exactly():
    for mask in canonical_masks(3, 9):
        ev = decide(Pattern(3, mask))
        if ev.method == "counterexample" and not ev.details.get("poles_only"):
            break
    else:  # pragma: no cover
        pytest.fail("no counterexample at order 3")
    a = [sp.Rational(v) for v in ev.details["a"]]
    c = [sp.Rational(v) for v in ev.details["c"]]
    sol = solve_at(Pattern(3, mask), a, c)
    assert sol["degree"] == ev.details["degree"] > 0 and sol["real"] == []
    roots = np.roots([float(v) for v in sp.Poly(sol["_e"], sol["_t"]).all_coeffs()])
    assert np.all(np.abs(roots.imag) > 1e-9)


def test_certified_root_proves_a_real_root_and_refuses_none():
    x, y = sp.symbols("x y")
    root = certified_real_root([x**2 - 2, y - x], [x, y], seed=3)
    assert root is not None and abs(abs(root.values[0]) - 2**0.5) < 1e-12 and root.nonzero
    assert certified_real_root([x**2 + 1, y], [x, y], seed=3) is None


@pytest.mark.slow
def test_the_search_on_dask_local_and_running_clusters_gives_the_serial_atlas(atlas2, tmp_path):
    # in a child process: dask's worker processes leave a multiprocessing resource tracker
    # behind, which the signal tests of this session would count as a stray child
    code = (
        "import json, sys, symctl\n"
        "from distributed import LocalCluster\n"
        "A = symctl.atlas(2, workers=2, checkpoint=sys.argv[1])\n"
        "with LocalCluster(n_workers=1, dashboard_address=':0', silence_logs=40) as cluster:\n"
        "    B = symctl.atlas(1, scheduler=cluster.scheduler_address)\n"
        "print(json.dumps([[p.mask for p in c.representatives] for c in B.classes]))\n"
        "print(json.dumps([[p.mask for p in c.representatives] for c in A.classes]))\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", code, str(tmp_path / "ck.jsonl")],
        capture_output=True,
        text=True,
        timeout=240,
        check=True,
    )
    lines = run.stdout.strip().splitlines()
    masks = json.loads(lines[-1])
    assert masks == [[p.mask for p in c.representatives] for c in atlas2.classes]
    on_a_running_cluster = json.loads(lines[-2])  # --scheduler ADDRESS
    assert on_a_running_cluster == [
        [p.mask for p in c.representatives] for c in symctl.atlas(1, workers=1).classes
    ]
    resumed = symctl.atlas(2, workers=1, checkpoint=tmp_path / "ck.jsonl")
    assert resumed.stats["resumed"] == resumed.stats["canonical"]
    assert [c.label for c in resumed.classes] == [c.label for c in atlas2.classes]


def test_a_checkpoint_of_another_search_is_refused(tmp_path):
    path = tmp_path / "ck.jsonl"
    symctl.atlas(1, workers=1, checkpoint=path)
    with pytest.raises(ParameterError, match="another search"):
        symctl.atlas(2, workers=1, checkpoint=path)


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"order": 0}, ParameterError, "order"),
        ({"order": 5}, ParameterError, "order"),
        ({"order": "2"}, SymctlTypeError, "order"),
        ({"order": 2, "delays": "axon"}, ParameterError, "delays"),
        ({"order": 2, "workers": 0}, ParameterError, "workers"),
        ({"order": 2, "max_size": 99}, ParameterError, "max_size"),
    ],
)
def test_bad_atlas_arguments_are_refused_with_their_name(kwargs, error, match):
    with pytest.raises(error, match=match):
        symctl.atlas(**kwargs)


@pytest.mark.parametrize(
    ("G2", "match"),
    [
        (1 / (z**2 - z / 2), "N = G2"),
        (1 + 1 / (z - 2), "order 2"),
        (z**3 / (z**2 + 1), "proper"),
    ],
)
def test_realize_refuses_a_G2_it_cannot_take(atlas2, G2, match):
    with pytest.raises(symctl.SymctlError, match=match):
        atlas2.classes[0].realize(G2)


def test_atlas_json_lists_every_class_with_patterns_and_evidence(atlas2):
    data = json.loads(json.dumps(atlas2.to_dict()))
    assert data["order"] == 2 and len(data["classes"]) == len(atlas2.classes)
    first = data["classes"][0]
    assert {"label", "neurons", "synapses", "branches", "universal", "evidence", "patterns"} <= set(
        first
    )
    assert first["patterns"][0]["F"] == [[1, 1], [1, 0]]


def test_cli_writes_the_atlas_and_refuses_a_bad_order(tmp_path):
    from symctl.cli import main

    out = tmp_path / "atlas"
    assert main(["atlas", "--order", "2", "--out", str(out), "--no-pdf", "--drawings", "2"]) == 0
    names = {p.name for p in out.iterdir()}
    assert {"atlas.json", "atlas.md", "atlas.tex", "atlas_overview.png", "class_A1.png"} <= names
    assert (
        "nine" not in (out / "atlas.md").read_text()
        and "9 universal" in (out / "atlas.md").read_text()
    )
    assert not (tmp_path / "atlas.progress.jsonl").exists()
    assert main(["atlas", "--order", "0", "--out", str(tmp_path / "bad")]) == 2


@pytest.fixture(scope="module")
def paper_candidates(atlas2):
    G = -0.0459719 / (z**2 + 0.580041 * z + 0.351813)
    return symctl.circuits_for(G, symctl.DelayGraph.chain([1, 1]), atlas=atlas2)


def test_circuits_for_finds_the_papers_simplified_circuits_with_their_epsilon(paper_candidates):
    degenerate = {
        c.circuit_class.representatives[0].text: c for c in paper_candidates if c.degenerate
    }
    no_m1 = degenerate["11 10 | 10 | 10"]  # controllable canonical without M_1 (states swapped)
    no_m2 = degenerate["01 11 | 01 | 10"]
    e1, e3 = (float(e) for e in no_m1.eps)
    assert abs(-0.351813 + e1 * e3) < 1e-8  # K2 + eps1 eps3 = 0
    e1, e3 = (float(e) for e in no_m2.eps)
    assert abs(-0.580041 - e1 - e3) < 1e-8  # K1 - eps1 - eps3 = 0
    for c in (no_m1, no_m2):
        assert c.check and c.compatible and c.n_neurons == 4


def test_circuits_for_is_ranked_with_the_minimum_neuron_circuit_first(paper_candidates):
    ranked = [(c.n_neurons, c.n_synapses) for c in paper_candidates]
    assert ranked == sorted(ranked) and ranked[0][0] == 4
    generic = [c for c in paper_candidates if not c.degenerate]
    assert len(generic) == 9 and all(c.check for c in generic)


def test_circuits_for_refuses_symbolic_gains_and_unrealizable_orders():
    with pytest.raises(ParameterError, match="numeric"):
        symctl.circuits_for(symctl.controller_tf(2))
    with pytest.raises(ParameterError, match="order"):
        symctl.circuits_for(sp.Integer(3), sensor_delay=0, actuator_delay=0)  # G2 of order 0


@settings(max_examples=examples(60), deadline=None)
@given(st.integers(min_value=0, max_value=2**15 - 1))
def test_pattern_neuron_count_is_the_circuits(mask):
    from symctl.circuitatlas.circuitclass import circuit_of

    p = Pattern(3, mask)
    if generic_rank(p).minimal:
        assert p.n_neurons == circuit_of(p).n_neurons


@pytest.mark.slow
def test_order_4_sparsest_classes_include_the_controllable_canonical_circuit():
    A = symctl.atlas(4, max_neurons=2, workers=1)
    assert not A.stats["complete"] and A.stats["skipped"] > 0
    best = A.sparsest()
    assert best.n_neurons == 2 and best.universal and best.evidence.proved
    a, c = sp.symbols("a0:4"), sp.symbols("c0:4")
    G2 = 1 + sum(c[i] * z**i for i in range(4)) / (z**4 + sum(a[i] * z**i for i in range(4)))
    ccf = Pattern.of(symctl.controllable_canonical(G2)).canonical()
    assert any(ccf in c.representatives for c in A.universal_classes)


@pytest.mark.slow
@pytest.mark.parametrize("address", ["not an address", "tcp://127.0.0.1:9"])
def test_an_unreachable_scheduler_is_one_line_exit_2_and_writes_nothing(tmp_path, capsys, address):
    from symctl.cli import main

    out = tmp_path / "atlas"
    assert main(["atlas", "--order", "1", "--scheduler", address, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("symctl: error: --scheduler:")
    assert sorted(p.name for p in tmp_path.iterdir()) == []


_coeff = st.fractions(min_value=-3, max_value=3, max_denominator=7)


@pytest.mark.slow
@settings(max_examples=examples(60), deadline=None)
@given(_coeff, _coeff, _coeff, _coeff, _coeff.filter(lambda v: v != 0))
def test_the_sparsest_order_2_class_realizes_any_rational_G2_in_closed_form(
    atlas2, a0, a1, c0, c1, N
):
    G2 = sp.Rational(N) + (sp.Rational(c1) * z + sp.Rational(c0)) / (
        z**2 + sp.Rational(a1) * z + sp.Rational(a0)
    )
    cls = atlas2.sparsest()
    try:
        R = cls.realize(G2)
    except (NotRealizableError, ParameterError):
        # only on a measure-zero set: a pole-zero cancellation (then G2 has a lower order) or
        # a coefficient that the closed form puts into an entry (F = [[-a1, 1], [-a0, 0]],
        # M = [c1, -c0/a0]): zero there, the entry would leave the pattern
        a_poly = z**2 + sp.Rational(a1) * z + sp.Rational(a0)
        b_poly = sp.Rational(c1) * z + sp.Rational(c0)
        assert sp.resultant(b_poly, a_poly, z) == 0 or 0 in (a0, a1, c0, c1)
        return
    assert Pattern.of(R).canonical() == cls.representatives[0]
    assert symctl.check_realization(R, G2, "exact")


def test_a_cut_or_edited_checkpoint_is_redone_from_the_bad_line(atlas2, tmp_path):
    path = tmp_path / "ck.jsonl"
    symctl.atlas(2, workers=1, checkpoint=path)
    lines = path.read_text().splitlines()
    path.write_text(
        "\n".join([*lines[:2], '[{"mask": "x"}]', lines[2][: len(lines[2]) // 2]]) + "\n"
    )
    again = symctl.atlas(2, workers=1, checkpoint=path)
    assert 0 < again.stats["resumed"] < again.stats["canonical"]
    assert [c.representatives for c in again.classes] == [c.representatives for c in atlas2.classes]


def test_a_checkpoint_that_is_a_folder_is_a_clear_error(tmp_path):
    with pytest.raises(ParameterError, match="checkpoint: cannot use"):
        symctl.atlas(1, workers=1, checkpoint=tmp_path)


def test_the_poles_alone_refute_a_pattern_whose_F_cannot_have_complex_poles_of_some_size():
    # F = [[f11, f12, 0], [0, f22, f23], [f31, 0, 0]]: det(zI - F) = z (z - f11)(z - f22) - p,
    # so (f11 + f22)^2 >= 4 f11 f22 bounds the reachable cubics: an open set of complex poles
    # is out of reach whatever H and M are
    p = Pattern.from_matrices([[1, 1, 0], [0, 1, 1], [1, 0, 0]], [1, 1, 0], [1, 1, 1])
    ev = decide(p)
    assert ev.universal is False and ev.method == "counterexample" and ev.details["poles_only"]
    a = [sp.Rational(v) for v in ev.details["a"]]
    # the sampled cubic z^3 + a2 z^2 + a1 z + a0 needs f11 + f22 = -a2 and f11 f22 = a1
    assert a[2] ** 2 - 4 * a[1] < 0


@pytest.mark.slow
def test_a_second_run_replaces_the_first_runs_folder(tmp_path):
    from symctl.cli import main

    out = tmp_path / "atlas"
    for _ in range(2):  # the folder of an earlier run is replaced, not refused
        assert main(["atlas", "--order", "1", "--out", str(out), "--no-pdf"]) == 0
    assert (out / "atlas.json").exists()
