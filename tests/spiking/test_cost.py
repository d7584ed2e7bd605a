"""spiking_cost: the neurons and spikes each circuit needs to stay near the linear loop."""

from __future__ import annotations

import json

import numpy as np
import pytest
from helpers import need_spiking

from symctl import ParameterError, SpikingCost, SymctlTypeError, spiking_cost

need_spiking("nengo")


@pytest.fixture(scope="module")
def small(derived_T2):
    return spiking_cost(derived_T2, circuits=["ifp", "A16", "A17"], neurons=(10, 100), seeds=2)


def _made(deviation, spikes, neurons=(10, 100, 1000)):
    d, s = np.asarray(deviation, float), np.asarray(spikes, float)
    return SpikingCost(("a",), (2,), (1.0,), neurons, d.shape[-1], (0.05, 0.01), d, s)


def test_needed_neurons_interpolate_in_log_n_between_the_bracketing_sizes():
    cost = _made([[[0.2], [0.02], [0.004]]], [[[1e3], [1e4], [1e5]]])
    n5, s5 = cost.needed(0.05)
    # deviation 0.2 -> 0.02 over 10 -> 100: 0.05 lies at log10 N = 1 + log(4) / log(10)
    assert n5[0, 0] == pytest.approx(40.0)
    assert s5[0, 0] == pytest.approx(4e3)
    n1, _ = cost.needed(0.01)
    assert 100 < n1[0, 0] < 1000
    assert cost.needed(0.5)[0][0, 0] == 10  # the smallest size already holds
    assert np.isinf(cost.needed(0.001)[0][0, 0])  # no size reaches it


def test_the_cost_is_the_median_over_seeds_with_its_range():
    cost = _made([[[0.2, 0.2, 0.2], [0.04, 0.02, 0.06], [0.01, 0.01, 0.01]]], np.ones((1, 3, 3)))
    row = cost.table()[0]
    lo, hi = row["N@5% range"]
    assert lo < row["N@5%"] < hi
    assert row["neurons@5%"] == pytest.approx(2 * row["N@5%"])


def test_every_circuit_runs_at_every_size_and_seed_and_more_neurons_help(small):
    assert small.deviation.shape == small.spikes.shape == (3, 2, 2)
    assert small.populations == (1, 4, 4) and small.atlas_classes == ("A16", "A17")
    assert (small.deviation[:, 1].mean(axis=1) < small.deviation[:, 0].mean(axis=1)).all()
    assert (small.spikes[:, 1] > small.spikes[:, 0]).all()
    assert set(small.ranking()) == set(small.ranking("spikes")) == {"ifp", "A16", "A17"}


def test_the_finding_is_computed_from_the_runs(small):
    fewest = small.fewest_neurons_cheapest()
    assert fewest == (small.ranking("spikes")[0] == "ifp")
    assert ("is the cheapest" if fewest else "is not the cheapest") in small.finding()
    atlas = small.finding(small.atlas_classes)
    assert "of A16, A17: 4 neurons each" in atlas
    assert small.fewest_neurons_cheapest(small.atlas_classes)  # two of two have the fewest


def test_the_summary_is_plain_json_and_the_cost_pickles(small):
    import pickle

    data = json.loads(json.dumps(small.summary(), allow_nan=False))
    assert data["neurons"] == [10, 100] and data["seeds"] == 2
    assert {r["circuit"] for r in data["circuits"]} == {"ifp", "A16", "A17"}
    assert set(data["circuits"][0]["cost"]) == {"5%", "1%"}
    assert data["finding"] == small.finding()
    assert pickle.loads(pickle.dumps(small)) == small
    assert SpikingCost.from_dict(json.loads(json.dumps(small.to_dict()))) == small


def test_an_interrupted_sweep_resumes_from_its_checkpoint(derived_T2, tmp_path):
    path = tmp_path / "sweep.jsonl"
    seen = []
    first = spiking_cost(derived_T2, circuits=["ifp"], neurons=(10,), seeds=2, checkpoint=path)
    lines = path.read_text().splitlines()
    path.write_text("\n".join(lines[:-1]) + '\n[{"cut": ')  # the last task lost, a line cut
    again = spiking_cost(
        derived_T2,
        circuits=["ifp"],
        neurons=(10,),
        seeds=2,
        checkpoint=path,
        progress=lambda done, total: seen.append((done, total)),
    )
    assert again == first
    assert seen == [(0, 2), (2, 2)]  # the one task (both seeds) ran again
    seen.clear()
    spiking_cost(
        derived_T2,
        circuits=["ifp"],
        neurons=(10,),
        seeds=2,
        checkpoint=path,
        progress=lambda *a: seen.append(a),
    )
    assert seen == [(2, 2)]  # nothing left to run


def test_a_checkpoint_of_another_sweep_is_refused(derived_T2, tmp_path):
    path = tmp_path / "sweep.jsonl"
    spiking_cost(derived_T2, circuits=["ifp"], neurons=(10,), seeds=1, checkpoint=path)
    with pytest.raises(ParameterError, match="checkpoint"):
        spiking_cost(
            derived_T2, circuits=["ifp"], neurons=(10,), seeds=1, checkpoint=path, steps=30
        )


def test_bad_arguments_name_themselves(derived_T2):
    with pytest.raises(ParameterError, match="neurons"):
        spiking_cost(derived_T2, neurons=(0, 10))
    with pytest.raises(ParameterError, match="neurons"):
        spiking_cost(derived_T2, neurons=(10, 10))
    with pytest.raises(ParameterError, match="circuits"):
        spiking_cost(derived_T2, circuits=["nobody"])
    with pytest.raises(ParameterError, match="tolerances"):
        spiking_cost(derived_T2, tolerances=(1.5,))
    with pytest.raises(ParameterError, match="circuits"):
        spiking_cost(derived_T2.gains)
    with pytest.raises(SymctlTypeError, match="source"):
        spiking_cost("paper")
    with pytest.raises(ParameterError, match="workers"):
        spiking_cost(derived_T2, workers=0)


def test_the_dask_path_gives_the_same_cost_as_this_process(derived_T2, small):
    both = spiking_cost(
        derived_T2, circuits=["ifp", "A16", "A17"], neurons=(10, 100), seeds=2, workers=2
    )
    # the same runs; the workers' single-threaded BLAS may round the decoders otherwise
    assert both.circuits == small.circuits and both.peak == small.peak
    np.testing.assert_allclose(both.deviation, small.deviation, rtol=1e-3)
    np.testing.assert_allclose(both.spikes, small.spikes, rtol=1e-3)


def test_a_sweep_stopped_midway_resumes_where_it_stopped(derived_T2, tmp_path):
    path = tmp_path / "sweep.jsonl"
    kw = {"circuits": ["ifp", "A17"], "neurons": (10,), "seeds": 1, "checkpoint": path}

    def stop(done, total):
        if done:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        spiking_cost(derived_T2, progress=stop, **kw)
    assert len(path.read_text().splitlines()) == 2  # the header and the one task finished
    seen = []
    whole = spiking_cost(derived_T2, progress=lambda *a: seen.append(a), **kw)
    assert seen == [(1, 2), (2, 2)]
    assert whole == spiking_cost(derived_T2, circuits=["ifp", "A17"], neurons=(10,), seeds=1)
