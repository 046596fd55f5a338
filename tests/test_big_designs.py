"""Big designs: the parts that replace all-pairs and all-planks loops by near-linear ones
give exactly what the quadratic definitions give (box pairs by sort and sweep, the planks
that carry each plank); the memory bounds change no result (an implicit condensation,
the sensitivity in blocks, a capped cache of factored contact states, models free of
reference cycles); a big design's suggestions stay near its violations; and a design too
big to check is refused in one line with exit code 2."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from furncheck.geometry.boxes import meeting_pairs, overlapping_pairs

DESIGNS = Path(__file__).resolve().parent.parent / "designs"


def _all_pairs(lo, hi, slack, strict):
    """The definition: every pair i < j compared on every axis, row-major."""
    if strict:
        meet = np.all((lo[:, None, :] < hi[None, :, :] - slack)
                      & (lo[None, :, :] < hi[:, None, :] - slack), axis=2)
    else:
        meet = np.all((lo[:, None, :] <= hi[None, :, :] + slack)
                      & (lo[None, :, :] <= hi[:, None, :] + slack), axis=2)
    return np.argwhere(np.triu(meet, k=1))


_coordinate = st.integers(0, 12).map(lambda k: 0.25 * k)     # ties and touching faces


@settings(max_examples=150, deadline=None, derandomize=True)
@given(st.lists(st.tuples(_coordinate, _coordinate, _coordinate,
                          _coordinate, _coordinate, _coordinate), min_size=0, max_size=30),
       st.sampled_from([0.0, 0.001, 0.25, 0.5]))
def test_box_pairs_are_the_all_pairs_ones(boxes, slack):
    """Sort and sweep finds exactly the pairs of the all-pairs comparison, in the same
    order, for meeting (<= with + slack) and overlapping (< with - slack) boxes; the
    coordinates are on a 0.25 grid, so boxes tie, touch, and meet exactly at the slack."""
    corners = np.array(boxes, dtype=float).reshape(-1, 2, 3)
    lo, hi = corners.min(axis=1), corners.max(axis=1)
    assert np.array_equal(meeting_pairs(lo, hi, slack), _all_pairs(lo, hi, slack, False))
    assert np.array_equal(overlapping_pairs(lo, hi, slack), _all_pairs(lo, hi, slack, True))


def test_box_pairs_of_a_row_of_touching_boxes():
    """Five unit cubes in a row along x, each touching the next: with no slack the
    neighbours meet (4 pairs), none overlap; a slack of 1.0 reaches the next but one too
    (4 + 3 pairs: 2 <= 1 + 1); "overlapping by more than -1.0" holds for the neighbours
    only (the next but one starts at 2, not below 1 + 1)."""
    lo = np.array([[k, 0.0, 0.0] for k in range(5)])
    hi = lo + 1.0
    assert meeting_pairs(lo, hi, 0.0).tolist() == [[0, 1], [1, 2], [2, 3], [3, 4]]
    assert overlapping_pairs(lo, hi, 0.0).tolist() == []
    assert len(meeting_pairs(lo, hi, 1.0)) == 7
    assert overlapping_pairs(lo, hi, -1.0).tolist() == [[0, 1], [1, 2], [2, 3], [3, 4]]


def _carriers_by_definition(n, pairs, grounded):
    """Per plank: take it away, search from the other grounded planks, keep the
    neighbours reached (one search per plank)."""
    neighbours = [set() for _ in range(n)]
    for a, b in pairs:
        neighbours[a].add(b)
        neighbours[b].add(a)
    out = []
    for removed in range(n):
        reached = {k for k in grounded if k != removed}
        frontier = list(reached)
        while frontier:
            k = frontier.pop()
            for other in neighbours[k] - reached - {removed}:
                reached.add(other)
                frontier.append(other)
        out.append(neighbours[removed] & reached)
    return out


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.integers(1, 14).flatmap(lambda n: st.tuples(
    st.just(n),
    st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1))
             .filter(lambda p: p[0] != p[1]), max_size=3 * n),
    st.sets(st.integers(0, n - 1), max_size=n))))
def test_carriers_match_the_definition(graph):
    """The one-search answer equals the one-search-per-plank definition on random joint
    graphs: repeated joints, planks on nothing, several grounded planks, cycles."""
    from furncheck.statics.carrying import carriers

    n, pairs, grounded = graph
    assert carriers(n, pairs, grounded) == _carriers_by_definition(n, pairs, grounded)


def test_carriers_of_a_shelf_and_a_hanging_lip():
    """Two sides (0, 1) on the floor with a shelf (2) nailed between them, a lip (3) nailed
    under the shelf only: the sides carry the shelf and the shelf braces each side (it
    still reaches the other side's floor), the lip carries nothing and the shelf is the
    lip's only carrier."""
    from furncheck.statics.carrying import carriers

    assert carriers(4, [(0, 2), (1, 2), (2, 3)], {0, 1}) == [{2}, {2}, {0, 1}, {2}]


def _shelving(columns, rows, model, heavy_kg=None):
    import sys
    from pathlib import Path

    from furncheck.design.model import with_model

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    from shelving import shelving_wall

    return with_model(shelving_wall(columns, rows, heavy_kg=heavy_kg), model)


@pytest.mark.parametrize("model", ["elastic", "rigid"])
def test_implicit_condensation_solves_as_the_stored_one(model, monkeypatch):
    """A condensation too large to keep X = A_ii^-1 A_ig (forced here by a limit of 0
    bytes) sums S0 a few columns at a time and solves for X x_g: the same statics as the
    stored X up to round-off, in both large paths (a 73-plank wall: 438 rigid plank
    displacements, above DENSE_PLANKS_MAX, and its elastic model's beams), for the
    case's solve and for the sensitivity's many right-hand sides."""
    from furncheck import tolerances as tol
    from furncheck.geometry import analyze
    from furncheck.statics import build_model, solve_load_case, solve_system

    design = _shelving(8, 8, model)
    geometry = analyze(design)
    results = []
    for limit in (tol.CONDENSED_DENSE_BYTES, 0):
        monkeypatch.setattr(tol, "CONDENSED_DENSE_BYTES", limit)
        statics_model = build_model(design, geometry)
        assert (statics_model.condensation.reduced is None) == (limit == 0)
        statics = solve_load_case(statics_model, design.load_cases[0])
        rhs = np.random.default_rng(1).normal(size=(len(statics.state), 3))
        results.append((statics.joint_wrenches, statics.contact_forces,
                        solve_system(statics_model, statics.holding, rhs)))
    for stored, implicit in zip(*results):
        assert np.allclose(implicit, stored, rtol=1e-9, atol=1e-9 * np.abs(stored).max())


def _linearized(design):
    from furncheck.sensitivity import Linearization

    return Linearization(design, design.load_cases[0], bolted=True, one_sided=True)


def _rates(sens):
    return [sens.joint_wrenches, sens.contact_forces, sens.joint_lengths, sens.plank_sags,
            sens.plank_spans, sens.plank_stresses]


def test_sensitivity_in_blocks_is_the_sensitivity_at_once(monkeypatch):
    """The elastic cabinet's 224 DOFs solved one DOF per block (a block limit of 1 byte)
    and its planks read 28 at a time (a batch of 28 planks) give the rates of one block
    and one stacked pass: every DOF's right-hand side, solve and planks are its own, the
    blocks only bound the memory.  Equal to round-off: a solve of one right-hand side
    rounds differently from a solve of 224 (measured: 1.3e-12 of the largest joint rate,
    4e-11 of the largest stress rate, whose one-sided difference over the small assembly
    step amplifies round-off), so within 1e-9 of each kind's largest rate; the catalog's
    designs fit one block and their JSON stays the same byte for byte."""
    from furncheck import tolerances as tol
    from furncheck.design import load_design
    from furncheck.dofs import all_dofs

    design = load_design(str(DESIGNS / "cabinet-28.yaml"))
    dofs = all_dofs(design)
    whole = _linearized(design).derivatives(dofs)
    monkeypatch.setattr(tol, "SENSITIVITY_BLOCK_BYTES", 1)
    monkeypatch.setattr(tol, "PLANK_BATCH", 28)
    blocked = _linearized(design).derivatives(dofs)
    assert blocked.dofs == whole.dofs and len(whole.dofs) > 100
    for a, b in zip(_rates(blocked), _rates(whole)):
        assert a.shape == b.shape
        assert np.abs(a - b).max(initial=0.0) <= 1e-9 * np.abs(b).max(initial=0.0)


def test_plank_rates_of_a_big_model_only_near_its_dofs(monkeypatch):
    """Above SENSITIVITY_ALL_PLANKS (forced to 0 here) the sag and stress rates are read
    only for the planks the DOFs change and the planks jointed to them.  Moving shelf1_1
    of a 3-bay, 3-row wall up changes that shelf alone (its ends slide along its sides),
    so its rates and its two sides' (side1, side2) are read, equal to the full read's,
    and every other plank's are 0 (in the full read the other planks' sag and stress
    move a little with the wall; no span but the moved shelf's changes); the joint and
    contact rates are the full ones."""
    from furncheck import tolerances as tol
    from furncheck.dofs import parse_dof

    design = _shelving(3, 3, "elastic")
    dofs = [parse_dof(design, "shelf1_1.z")]
    linear = _linearized(design)
    whole = linear.derivatives(dofs)
    monkeypatch.setattr(tol, "SENSITIVITY_ALL_PLANKS", 0)
    near = _linearized(design).derivatives(dofs)
    local = [design.planks[i].id for i in linear.model.planks]
    read = [local.index(name) for name in ("side1", "side2", "shelf1_1")]
    others = [k for k in range(len(local)) if k not in read]
    for a, b in zip(_rates(near)[3:], _rates(whole)[3:]):
        assert np.allclose(a[:, read], b[:, read], rtol=1e-9, atol=0.0)
        assert not np.any(a[:, others])
    assert np.any(whole.plank_sags[:, others]) and np.any(whole.plank_stresses[:, others])
    for a, b in zip(_rates(near)[:3], _rates(whole)[:3]):
        assert np.array_equal(a, b)


def test_nearest_planks_by_joint_rings_then_distance():
    """Around shelf1_1 of a 3-bay, 3-row wall (bays 412 mm apart, shelves 250 mm apart):
    ring 0 the shelf, ring 1 its two sides, ring 2 the shelves on those sides, nearest
    first: the shelves above and below it in its bay (250 mm) before the shelves at its
    height in the next bays (412 mm); five planks are those, sorted by index."""
    from furncheck.geometry import analyze
    from furncheck.neighbourhood import nearest_planks

    design = _shelving(3, 3, "rigid")
    ids = [p.id for p in design.planks]
    near = nearest_planks(design, analyze(design), [ids.index("shelf1_1")], 5)
    assert sorted(ids[k] for k in near) == sorted(
        ["shelf1_1", "side1", "side2", "shelf1_0", "shelf1_2"])
    assert near == sorted(near)


def test_big_design_suggestions_change_only_planks_near_the_violation(monkeypatch):
    """With the big-design limit forced down (SUGGEST_ALL_PLANKS 4, SUGGEST_NEAR_PLANKS
    3), an 11-plank wall whose middle shelf sags under 20 kg gets suggestions that change
    only that shelf and its two sides, among them the same move of its side2 as the
    search over every DOF finds (the move's direction and line search involve that side
    alone, so restricting the others away changes nothing of it; widening the shelf,
    which the search found while the shelf's beam spread the 20 kg over its width, no
    longer helps since the shelf is checked as a plate too, ``statics.plates``: under a
    point load a deeper plate sags little less); the explanation counts the other 8
    planks' 64 DOFs as left out."""
    from furncheck import tolerances as tol
    from furncheck.suggest import suggest_design

    design = _shelving(2, 4, "elastic", heavy_kg=20.0)
    everything = suggest_design(design)
    monkeypatch.setattr(tol, "SUGGEST_ALL_PLANKS", 4)
    monkeypatch.setattr(tol, "SUGGEST_NEAR_PLANKS", 3)
    near = suggest_design(design)
    assert [v.where for v in near.report.violations] == ["shelf1_2"]
    changed = {name.split(".")[0] for s in near.suggestions for name in s.dofs}
    assert changed and changed <= {"shelf1_2", "side1", "side2"}
    moved = [s for s in near.suggestions if s.dofs == ("side2.x",)]
    assert moved and moved[0].changes == next(
        s.changes for s in everything.suggestions if s.dofs == ("side2.x",))
    assert near.explanation.tried.far == (11 - 3) * 8      # the other 8 planks' DOFs
    assert everything.explanation.tried.far == 0


@pytest.mark.parametrize("command", [["validate"], ["suggest"], ["range", "top.z"]])
def test_a_design_too_big_is_refused_in_one_line_with_exit_2(command, monkeypatch):
    """The splayed coffee table stands on four legs, each on one node of the ground
    (rigid: one per plank; elastic: the leg's foot), 4 x 6 = 24 unknowns of the dense
    contact system.  With the limit set to 18 (three nodes) every command refuses it
    before solving: one line naming the file, the 4 nodes and 24 unknowns, exit code 2,
    no traceback."""
    from click.testing import CliRunner

    from furncheck import tolerances as tol
    from furncheck.cli.main import main

    monkeypatch.setattr(tol, "MAX_GROUND_UNKNOWNS", 18)
    path = str(DESIGNS / "coffee-table-splayed.yaml")
    result = CliRunner().invoke(main, [command[0], path, *command[1:]])
    assert result.exit_code == 2
    assert result.exception is None or isinstance(result.exception, SystemExit)
    lines = result.output.strip().splitlines()
    message = next(line for line in lines if "too big to check" in line)
    assert path in message
    assert "sit on 4 nodes, a dense contact system of 24 unknowns" in message
    assert "at most 18, 3 nodes" in message
    assert "Traceback" not in result.output



@pytest.mark.parametrize("command", [["validate"], ["suggest"], ["range", "b0.x"]])
def test_planks_drawn_on_top_of_one_another_are_refused_before_they_are_compared(
        command, tmp_path):
    """700 boards drawn in one place meet in 700 x 699 / 2 = 244,650 pairs, more than
    MAX_MEETING_PAIRS (200,000), each compared face by face at about 2 kB (2,000 such
    boards took 4.2 GB and 30 s before the contact system was refused): every command
    refuses the design first, one line naming the pairs, exit code 2; 600 of them
    (179,700 pairs) are still checked."""
    from click.testing import CliRunner

    from furncheck.cli.main import main

    def stack(count: int) -> str:
        path = tmp_path / f"stack{count}.yaml"
        path.write_text("furncheck: 1\nplanks:\n" + "".join(
            f"- {{id: b{k}, size: [100, 100], center: [0, 0, 6]}}\n" for k in range(count)))
        return str(path)

    result = CliRunner().invoke(main, [command[0], stack(700), *command[1:], "--model",
                                       "rigid"])
    assert result.exit_code == 2
    message = next(line for line in result.output.splitlines() if "too big" in line)
    assert "its 700 planks meet or overlap in 244650 pairs" in message
    assert "at most 200000" in message
    if command == ["validate"]:
        checked = CliRunner().invoke(main, ["validate", stack(600), "--model", "rigid",
                                            "--no-cache"])
        assert checked.exit_code in (0, 1) and "0 errors" in checked.output


@pytest.mark.parametrize("command", [["suggest"], ["range", "seat.x"]])
def test_the_pairs_limit_is_the_inputs_not_its_edits(command, monkeypatch):
    """The limit is asked of the design a command reads, not of the edits its search
    checks: with MAX_MEETING_PAIRS set to bench-tips' own count, an edit that adds a pair
    (a support under the seat) is a candidate like any other; the search ended in
    'internal error: DesignTooBig' (suggest) or blamed the input for the edit's count
    (range).  One pair fewer, the input is refused."""
    from click.testing import CliRunner

    from furncheck import tolerances as tol
    from furncheck.cli.main import main
    from furncheck.design import load_design
    from furncheck.geometry.analysis import meeting_count

    path = str(DESIGNS / "bench-tips.yaml")
    own = meeting_count(load_design(path))
    monkeypatch.setattr(tol, "MAX_MEETING_PAIRS", own)
    result = CliRunner().invoke(main, [command[0], path, *command[1:], "--model", "rigid"])
    assert result.exit_code == 0 and "too big" not in result.output, result.output
    monkeypatch.setattr(tol, "MAX_MEETING_PAIRS", own - 1)
    result = CliRunner().invoke(main, [command[0], path, *command[1:], "--model", "rigid"])
    assert result.exit_code == 2 and f"meet or overlap in {own} pairs" in result.output


def test_a_statics_model_is_freed_when_dropped():
    """A solved model (its condensation, factored contact states, planks' layout) holds no
    reference cycle: dropping the last reference frees it at once, not at the garbage
    collector's next full pass (a big design's line search drops a model of hundreds of MB
    per check)."""
    import gc
    import weakref

    from furncheck.design import load_design
    from furncheck.design.model import with_model
    from furncheck.geometry import analyze
    from furncheck.statics import build_model, solve_load_case

    for model_name in ("elastic", "rigid"):
        design = with_model(load_design(str(DESIGNS / "cabinet-28.yaml")), model_name)
        geometry = analyze(design)
        enabled = gc.isenabled()
        gc.disable()
        try:
            model = build_model(design, geometry)
            for case in design.load_cases:
                solve_load_case(model, case)
            alive = weakref.ref(model)
            del model
            assert alive() is None
        finally:
            if enabled:
                gc.enable()


def test_forgotten_contact_states_are_factored_again_to_the_same_numbers(monkeypatch):
    """With room for one factored contact state only (ANCHORED_CACHE_BYTES 1), the
    cabinet's four cases -- whose contact iterations meet several states -- solve to
    exactly the forces of an unbounded cache: a forgotten state is factored again from the
    same matrix."""
    from furncheck import tolerances as tol
    from furncheck.design import load_design
    from furncheck.geometry import analyze
    from furncheck.statics import build_model, solve_load_case

    design = load_design(str(DESIGNS / "cabinet-28.yaml"))
    geometry = analyze(design)
    solved, kept = [], []
    for limit in (tol.ANCHORED_CACHE_BYTES, 1):
        monkeypatch.setattr(tol, "ANCHORED_CACHE_BYTES", limit)
        model = build_model(design, geometry)
        solved.append([solve_load_case(model, case) for case in design.load_cases])
        kept.append(len(model.anchored_systems))
    assert kept[0] > 1 and kept[1] == 1
    for full, capped in zip(*solved):
        assert full.stability == capped.stability
        assert np.array_equal(full.joint_wrenches, capped.joint_wrenches)
        assert np.array_equal(full.contact_forces, capped.contact_forces)


@settings(max_examples=100, deadline=None, derandomize=True)
@given(st.lists(st.tuples(_coordinate, _coordinate, _coordinate), min_size=1, max_size=25),
       st.lists(st.tuples(_coordinate, _coordinate, _coordinate), min_size=1, max_size=25),
       st.sampled_from([0.0, 0.25, 0.5]))
def test_mirror_partners_near_pairs_are_the_all_pairs_ones(points, others, slack):
    """The centres within the slack of a mirrored centre, found through a k-d tree, are
    exactly the pairs of the all-pairs distance test, row-major (grid coordinates: pairs
    exactly at the slack, and coincident centres)."""
    from furncheck.suggest.symmetry import _near_pairs

    a, b = np.array(points), np.array(others)
    expected = np.argwhere(np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2) <= slack)
    assert np.array_equal(_near_pairs(a, b, slack), expected)


def test_trailing_schur_is_the_solved_one(monkeypatch):
    """S0 of a large elastic condensation read from the trailing block of one more LU (the
    grounded unknowns ordered last, their block shifted to be positive definite) equals S0
    summed from one solve per grounded unknown, to round-off (1e-10 of its largest
    entry), on the 73-plank wall forced onto the implicit path; and each way the case
    solves to the same forces."""
    from furncheck import tolerances as tol
    from furncheck.geometry import analyze
    from furncheck.statics import build_model, condense, solve_load_case

    design = _shelving(8, 8, "elastic")
    geometry = analyze(design)
    monkeypatch.setattr(tol, "CONDENSED_DENSE_BYTES", 0)
    read = []
    trailing_schur = condense._trailing_schur
    monkeypatch.setattr(condense, "_trailing_schur",
                        lambda *args: read.append(trailing_schur(*args)) or read[-1])
    found = []
    for limit in (tol.TRAILING_SCHUR_MAX, 0):       # trailing block, then solves
        monkeypatch.setattr(tol, "TRAILING_SCHUR_MAX", limit)
        model = build_model(design, geometry)
        statics = solve_load_case(model, design.load_cases[0])
        found.append((model.condensation.schur, statics.joint_wrenches,
                      statics.contact_forces))
    assert read[0] is not None and read[1] is None
    (trailing, *forces), (solved, *reference) = found
    assert np.abs(trailing - solved).max() <= 1e-10 * np.abs(solved).max()
    for a, b in zip(forces, reference):
        assert np.allclose(a, b, rtol=1e-7, atol=1e-9 * np.abs(b).max())
