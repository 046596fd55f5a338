"""Every numeric tolerance and solver constant of furncheck, in one place.

Physical constants and defaults come first, then geometric tolerances, then the
penalty stiffnesses and iteration limits of the statics solver.  Values are SI
(metres, newtons, kilograms, radians) unless the name says otherwise.
"""

GRAVITY = 9.81
"""m/s^2, acting along world -z."""

# --- defaults of a design file (contract section 1; the paper's 12 mm MDF) -------------
DEFAULT_THICKNESS = 0.012        # m
DEFAULT_DENSITY = 750.0          # kg/m^3
DEFAULT_NAIL_SPACING = 0.020     # m
DEFAULT_NAIL_PULL = 700.0        # N per nail (35 kN/m x 20 mm)
DEFAULT_NAIL_SHEAR = 190.0       # N per nail
DEFAULT_FRICTION = 0.5           # static Coulomb coefficient with the ground
DEFAULT_SAFETY_FACTOR = 1.0
DEFAULT_TOLERANCE = 0.0005       # m (0.5 mm)
DEFAULT_MODEL = "elastic"
"""The statics model of a file without ``model`` and without ``--model`` (contract sections
1 and 3): 'elastic', planks as beams; 'rigid' is the paper's model."""
MODELS = ("elastic", "rigid")

# elastic model (contract section 3a); sources in the README's "Material defaults"
DEFAULT_ELASTIC_MODULUS = 3.0e9    # Pa: EN 12369-1 mean E of MDF 12-19 mm (3000 N/mm^2),
                                   # above EN 622-5's 2500 minimum for 9-12 mm boards
DEFAULT_SHEAR_MODULUS = 0.8e9      # Pa: EN 12369-1 mean panel shear modulus of MDF.LA
DEFAULT_BENDING_STRENGTH = 22.0e6  # Pa: EN 622-5 minimum bending strength, MDF 9-12 mm
DEFAULT_CREEP = 0.5                # the Sagulator's "about 50 % more sag over time"
DEFAULT_SAG_LIMIT = 400.0          # the Sagulator: 1.5 x sag <= span / 400, i.e. initial
                                   # sag <= 0.02 in per foot (span / 600)
DEFAULT_NAIL_SLIP = 1.2e6          # N/m per nail: Eurocode 5 Table 7.1, K_ser = rho^1.5
                                   # d^0.8 / 30 for rho = 750 kg/m^3, d = 2.0 mm: 1192 N/mm
DEFAULT_NAIL_WITHDRAWAL = 1.0e6    # N/m per nail: an estimate (no published test of nails
                                   # in MDF): 25 d l_ef of screw approvals with d = 2 mm,
                                   # l_ef = 20 mm; 700 N at ~0.7 mm slip is the same

# --- geometry ---------------------------------------------------------------------------
JOINT_MAX_TILT_DEG = 60.0
"""Largest angle between an edge plank's end face and the face plank's face that still
forms a nail joint (a bevelled end).  Steeper contacts are not joints."""

NAIL_COUNT_EPS = 1e-6
"""Relative slack in floor(L / spacing), so 300 mm / 20 mm gives 15 nails despite rounding."""

MIN_JOINT_AREA_FRACTION = 1e-6
"""A touching region smaller than this fraction of the edge face's area is no joint."""

MIN_BEARING_SHARE = 0.5
"""A nail joint's touching region must be at least this share of the edge plank's
thickness wide across the joint line (its area over its length): nails are driven along
the middle of that band, so a narrower one puts them within a quarter of the thickness of
the face plank's edge, where they split out or miss (EN 1995-1-1 8.3.1.2 asks 5 d to 10 d
of edge distance for a nail, 10 to 20 mm for a 2 mm one: this is a floor, not that
spacing rule).  A shelf whose end covers 0.5 mm of its side is no joint but a near miss
(``disconnected``, with the bearing it has); resting joints, with no nails, keep any
touch."""

BEARING_EPS = 1e-9
"""m of round-off allowed in the bearing test (a region exactly MIN_BEARING_SHARE of the
thickness wide bears), and the least joint length a band's width is measured over."""

MAX_INPUT_PROBLEMS = 20
"""At most this many problems of one design file are reported (one line each); a file
that gets more is far from a design."""

NEAR_MISS_FACTOR = 20.0
"""Near misses (contract section 2): where an auto joint or a ground contact would be, a
gap or an overlap of more than the design's tolerance but at most this many times it (10
mm at the default 0.5 mm) is reported (``disconnected`` / ``floating``, with its size),
never silently left out: a leg 4 mm short is a slip of the drawing, not a design.  Farther
apart, the planks are taken to be apart on purpose (``furncheck.geometry.near``)."""

# --- statics: penalty constants (paper section 5.1, eq. 2) -------------------------------
JOINT_COMPLIANCE_T = 1e-10
"""m/N: epsilon^t, compliance of a joint's translational constraint (nails in shear and
withdrawal are stiff)."""

def joint_compliance_r(edge_thickness: float) -> float:
    """rad/(N m): epsilon^r of a joint whose edge plank is ``edge_thickness`` (m) thick.

    The paper's own lever model (eq. 4) resists a bending moment M by a nail couple with
    arm t/2, so a rotation theta stretches the nails by theta t/2 and the joint's bending
    stiffness is k_t (t/2)^2: epsilon^r = epsilon^t / (t/2)^2.  Equal epsilons in SI (the
    paper's 1e-5 for both) would make a 12 mm joint ~7000 times too stiff in bending and
    let closed frames (seat, legs, stretcher) carry phantom bending moments round the loop.
    """
    return JOINT_COMPLIANCE_T / (0.5 * edge_thickness) ** 2


CONTACT_STIFFNESS = 1e5
"""N/m: normal and tangential (friction anchor) spring stiffness of a ground contact.
Far softer than the joints (a 12 mm joint turns 1e-4 rad under 36 N m while a contact
sinks 1 mm under 100 N), so the assembly acts as one rigid body on springs."""

ELASTIC_CONTACT_STIFFNESS = 1e10
"""N/m: normal and anchor springs of a ground contact in the elastic model: ten thousand
times a 15-nail joint's spring (1.5e7 N/m), a hundred thousand times a table top's bending
stiffness, so that where the load goes is decided by the planks and joints (contract
section 3a), while the condensed systems stay well within double precision."""

BEAM_SEGMENTS = 1
"""Elastic model: a plank's beam has a node at least every 1/BEAM_SEGMENTS of its length,
besides its ends, its centre and the nodes where joints, contacts and loads act.  One (no
more nodes) is enough: the Timoshenko elements are exact at their nodes for end loads and
their own uniform load, and sag and stress are read inside them exactly
(``beams.element_interior``); more nodes change no result (a test refines to 8)."""

JOINT_PART_LENGTH = 0.1
"""m: elastic model: a nail joint whose row runs along a plank's beam (a batten along a
rail, a rail under a shelf's middle, a slat along a side) is modelled as parts of its
nail row, about one per this length of the row's reach along that beam (rounded to
whole parts, at most one per two nails), each a spring of its own at its own node
(``beams.nail_row_parts``, ``elastic.joint_part_counts``): the plank is held along the
row, not at its middle alone, and two planks nailed along each other bend together as
a nailed composite beam.  The parts' springs sum to the contract's one spring of the
whole row exactly (translations, the turn about the joint line, and S by the
parallel-axis rule), so planks that do not bend get the same joint wrenches as from one
spring.  A tenth of a metre: a plank between parts spans about 100 mm (a 12 mm MDF
shelf under 25 kg/m of books then sags 0.01 mm there), and a design's nodes grow by
about one per 100 mm of such a row."""

JOINT_PART_SHARE = 0.25
"""... or per this share of the beam the row runs along, where that is shorter: a short
plank nailed along its length (with 8 nails or more) is held at four places."""

JOINT_PART_NARROW = 8.0
"""A row stays whole where a plank whose beam it runs along would bend across its width,
as a plate, under what the row holds it against, which the one-beam model's rigid arms
from its axis to the parts would hold straight (``elastic.joint_part_counts``): the row
off the plank's middle (JOINT_PART_CORE), and the plank wider than this many thicknesses
(96 mm of 12 mm stock: a batten, a slat, a rail are narrower) where it is the row's face
plank (the row's force acts across its face: a shelf on a cleat, a top on its rails or
aprons) or lies level (JOINT_PART_LEVEL: its own load acts across its face: a shelf
nailed by its back edge, a shelf deeper than it is wide held by its ends).  Its joint
keeps the one spring at its middle, which overstates the board's sag (the sagging
message says so, ``validity._held_along``) rather than understating it; but where the
row alone holds the plank (``elastic.hung_planks``: a shelf nailed by its back edge onto
a rail, and nothing else), it is cut, and the plate check of the plank hung on the row
reads its bending across (``plate_supports._hangs_along``)."""

JOINT_PART_EDGE_NARROW = 16.0
"""... or wider than this many thicknesses (192 mm of 12 mm stock) where it is an upright
edge plank: the row's force acts in its plane, where it is stiff across its width, but
the row's moment about its line acts across its face (a coffee table's 400 mm end panel
under the top's end).  A rail on edge under a shelf, up to twice the stiffening rule's
deepest (8 thicknesses), is held along the shelf."""

JOINT_PART_LEVEL = 0.7071
"""A plank lies level when its face normal is within 45 degrees of the vertical (the
cosine, |n_z| >= this)."""

JOINT_PART_CORE = 0.25
"""... the row off the plank's middle: beyond this share of its half width from its
beam's axis (a spine rail along the middle of a top is within it)."""

SPAN_ACROSS_STIFFNESS = 1.0
"""Elastic model: a plank nailed along both its longer edges to panels spans across its
width (``elastic._spans_across``) where each panel holds its joint line straight
(``elastic._holds_straight``): bending in its own plane over the line's length L, the
panel gives at most this many times what the plank gives across its span s under the
same load, L^3 / (E_p t_p h^3) <= this x s^3 / (E w t^3) (h the panel's depth across
the line; w, t the plank's section width along the lines and its thickness).  Equal
compliances: where the panel gives less, the plank's bending across is what shows; where
it gives more, the two bend together along the line and the plank's beam along it is
the composite's.  A nightstand's 550 mm high side holds its 400 mm deep top's edge about
2,600 times stiffer than the top (388 mm across) bends, a 190 mm side hung on a wall
about 110 times; a 100 mm apron under a 1200 x 300 mm bench seat gives fourteen times
more than the seat across it: a rail, and the seat keeps its length."""

SPAN_ACROSS_STANDING = 0.5
"""... or where it stands on the floor along at least this share of the line (its floor
corners that far apart along it): a low side on the floor does not bend along it."""

SPAN_ACROSS_COVER = 0.75
"""... where the lines held straight cover at least this share of each of its two longer
edges (each share compared with a millimetre, NODE_MERGE, to spare).  A top whose sides
are shallower than it is deep overhangs them along its length: held along less than
this, its beam keeps its length and shows the overhang's bending along it, not its
bending across between the sides (a 400 mm deep top on 300 mm deep sides spans across;
on 290 mm sides its beam reads the 110 mm overhang, 0.46 mm under 40 kg at its middle,
and the plate check, ``statics.plates``, the top's bending across: 2.23 mm).  Three
quarters: a top overhanging its sides by 20 or 30 mm at the front, as tops do, is held
along nearly all of its edges."""

SPAN_ACROSS_CROSSING = 1.5
"""... and where its joint lines across its width (along its shorter side) held straight
by panels (rails across do not count: a drawer rail under its front edge) add up to less
than this many times that side: a top nailed to a back panel along one short edge as
well (held on three edges) still spans across, held at its back by the back's nail row
(a 388 x 400 nightstand top with a back, 40 kg at its centre: 1.56 mm, where a Mindlin
plate held on those three edges sags 0.90 mm with clamped and 2.23 mm with simply
supported edges, ``benchmarks/compare_plate.py``; along its depth its beam, held along
its length and at its end, read 0.04 mm); one nailed all round keeps the beam along its
longer side, as contract 3a has it, and the plate check reads its bending
(``statics.plates``).
One and a half, so that neither a back exactly as wide as the plank nor two such sit on
the edge of the rule."""

PLATE_HELD_SHARE = 0.25
"""Elastic model: a plank not standing on the floor whose joint lines held straight by
their other planks (``elastic._holds_straight``) cover at least this share of one of its
sides, on one line or on one side of its middle (their union, a millimetre, NODE_MERGE,
to spare), and hold it somewhere off that line too, is also checked as a plate
(``statics.plates``): held along them, its beam shows little of its bending, which
happens across it, between the lines (a step box's top nailed to its four sides read
0.02 mm under 80 kg where the plate sags 1.71 mm; a nightstand top on sides 290 mm
deep under its 400 mm depth).  A quarter: a table top's legs, 40 mm of a 1000 mm side,
hold its beam at its ends only, where the beam's bending is the plank's."""

PLATE_CELLS = 10
"""Elastic model: a plate plank's grid has about this many elements across its shorter
side (``plate_mesh.grid_lines``; its lines also pass through every support line's ends and every
load patch's edges).  Bilinear Mindlin elements with one-point shear: at 10, with the
shear made stiff (Kirchhoff's plate), a simply supported plate's centre deflection is
within 1.6 % of Navier's series under a uniform load and a central patch (400 x 400, 600 x
400, 1000 x 300), a strip's middle within 2 % of 5 q L^4 / 384 D plus its shear term
(``tests/test_plates.py``); at 8 the strip read 2.9 % low, at 12 the cabinet's check
took about 6 % longer."""

PLATE_CELL_FLOOR = 0.5
"""... but a plate's cells are never shorter than this share of its thickness: a plank
narrower than PLATE_CELLS x PLATE_CELL_FLOOR thicknesses (60 mm of 12 mm MDF) gets fewer
cells across it, and cells as long along it.  Its plate is then a strip, which its beam
reads as well (a plate's theory, thin or Mindlin's, does not resolve lengths shorter
than its thickness anyway).  Without it a range probe that narrowed a 488 mm shelf to
2 mm cut it into 2,327 x 10 cells, 98,241 unknowns, and took 0.3 s to factor; a
catalog plate is this narrow only in magazine-rack's 40 mm handle."""

PLATE_CELL_SLACK = 1e-3
"""An interval between a plate's grid lines up to this fraction of a cell longer than a
whole number of cells is cut into that number (``plate_mesh.grid_lines``): a design drawn in
whole millimetres has intervals of whole cells, which a sensitivity's step (1e-7 of the
design's size) must not cut into one more (its sag's rate read 3,000 times too large);
the cells are then at most 0.1 % longer than PLATE_CELLS makes them."""

PLATE_POISSON = 0.25
"""Elastic model: Poisson's ratio of a plate plank (its rigidity E t^3 / 12 (1 - nu^2)).
MDF is nearly isotropic in its plane; 0.25 is the Wood Handbook's value for MDF (as
MakeItFrom's MDF sheet cites it), and Ganev et al. (2005, Wood and Fiber Science 37(2))
found MDF's in-plane Poisson's ratio independent of its density.  Between 0.2 and 0.3 a
plate's deflection moves by about 3 %."""

PLATE_LOAD_PATCH = 0.05
"""m: a point load on a plate plank presses on a square this wide about its point (moved
onto the plank where it would overhang an edge): Eurocode 1 (EN 1991-1-1, 6.3.1.2 (5))
lets a floor's concentrated load Q_k act on a square of 50 mm side.  A plate's bending
stress under a true point is unbounded; over 50 mm a simply supported 400 mm square of
12 mm MDF under 40 kg reads 4.1 N/mm^2 by Navier's series, over 100 mm 3.0 (its centre
1.53 and 1.44 mm down)."""

PLATE_PATCH_CELLS = 4
"""... and each load patch is cut into this many elements each way, so that the largest
moment, under the patch, is read near its peak (one element per patch read 11 % low
against Navier's series; four, 2 to 4 % low)."""

PLATE_CACHE = 32
"""How many factored plates (``plate_mesh.plate_grid``) a process keeps: the planks alike in
a design (a bookcase's shelves), and a plank an edit leaves as it was in the many
checked designs of a ``range`` or ``suggest``, share one.  A 600 x 300 shelf's band is
about 0.3 MB, a 1200 x 600 top's with PLATE_GRID_LINES lines each way at most about
20 MB."""

PLATE_GRID_LINES = 60
"""At most this many grid lines each way in a plate (``plate_mesh.grid_lines``): where the
edges of many point loads (of one case: each case has its own grid) would pass it, they
are left out, and each load is shared by the elements it overlaps all the same (a 1.2 x
0.6 m top with 30 point loads took 87 MB and half a second to factor with them in)."""

PLATE_RATES_FROM = 0.8
"""The force sensitivities (``derivatives._plate_sides``) read how a plank's plate reading
changes with a DOF where that reading is the plank's (above its beam's) and uses at least
this share of its allowed sag or strength: each DOF that moves the plank or what holds it
factors a new plate (the cabinet's four cases: 452 plates, about a second; the paper's
Table 1 designs, whose plates hold with a quarter to spare, 10 to 20 % more time in
``suggest``).  Far from its limit a plate's rate barely steers a search; every
suggestion and range end is checked in full, plates included."""

PLATE_READINGS = 4096
"""How many plate readings (sag, span, stress of one plate under one case's loads, by
the plate's inputs and its loads) a process keeps (``plates._solved``): every check
reads its plates through them, so that a range's or a search's probe reads the plates
its edit left as they were without solving them again, and the force sensitivities
(``plates.plate_readings``) read a stepped design's plates case by case; about 0.5 to
2 kB each, a few megabytes in all."""

PLATE_DESIGNS = 4096
"""How many designs' plate inputs (which planks are plates, and each plate's
``plates._plate_key``) a process keeps for the force sensitivities
(``plates.plate_readings``: a DOF's stepped designs are linearized in every load case;
the designs themselves are not kept, only weak references to them)."""

PLATE_STEP_LINES = 1e-5
"""m: a stepped design's plate (``plates.same_grid``) reads the plate's rate only where
its grid lines lie within this of the design's plate's (a sensitivity's step moves a
support line by 1e-7 of the design's size, a few hundredths of a micrometre; a line
more or a cell cut otherwise moves lines by millimetres); elsewhere the DOF's rate is
its beam's."""

PLATE_BATCH = 64
"""A plate's distinct loads not yet read (planks alike share one factored plate: every
plank's loads in every case with the same patches) are solved this many at a time
(``plates._solved``): a
2,000-plank wall's 1,960 shelves at once held about 75 MB of moments and displacements;
in 64s, a few megabytes."""

PLATE_SLANT = 1e-6
"""A joint line whose direction, in a plate plank's plane, leans from both its axes by
more than this (its sine) is not a plate support (``plate_supports._support_segments``: the
grid runs along the plank's axes); a point load whose force leans off a plate plank's face
by this much or less pushes along it, not across (``plates._case_loads``: no patch)."""

SUPPORT_STATION_LENGTH = 0.25
"""m: elastic model: a plank that touches the floor or a wall along its beam (a board lying
on the floor, a kick board standing on its long edge, a shelf's back edge against a wall:
two of its corners on that support at the beam's two ends) is held by that support along
its length, not at its corners alone: each such edge gets a contact at every node of the
beam between its corners, where joints and loads act and at its centre, and at a grid of
nodes about this length apart (``stations.support_stations``), unilateral and with
friction like the corners.  What the support holds it with is reported at its corners
(``StaticsModel.corner_forces``: each station's force shared between the two corners of
its edge by the lever rule, so the reported forces have the same sum and moment, and
press and stay within their friction cones wherever the stations' do).  A quarter of a
metre: a point load or a joint has a station under it, so what spans between stations is
the plank's own weight and spread loads (a 300 x 12 mm MDF board with 100 kg of books
spread on a metre of it sags about 0.08 mm between stations 250 mm apart, w L^4 / 384 EI
for a span held on both sides), and a board on the floor adds
a node and two contacts per 250 mm; a finer grid changes its numbers by little more than
it costs the friction phase (at 100 mm, the Table-1 9-plank design's bottom board had
three stations, and its elastic suggestion step took 78 ms against 63)."""

SUPPORT_STATION_DEPTHS = 4.0
"""... or this many times the plank's depth across its support, where that is longer: a
kick board 80 mm deep on edge gets a station about every 320 mm (between them it acts
as a deep beam, its load carried to the stations in its plane; a 12 mm board lying flat
every 250 mm), so that a design's nodes and contacts grow by little more than what
changes its numbers."""

SAG_SAMPLES = 31
"""Elastic model: points inside each beam element where the deflection is read for the sag
and the moment for the stress (besides its ends and, for the stress, the peaks of its
moments): the sampled largest deviation of a span's deflection is within 1 - cos(pi / 64),
0.12 %, of the true one."""

SAG_ROUNDOFF = 1e-12
"""m: a plank's deviation from its supports' line or tangent this small is round-off (a
plank that does not bend: a magazine rack's end panel held by its slats at one node
deviates 1e-16 to 1e-13 m).  Choosing the measure nearest its limit (``sag.plank_sags``),
such deviations tie and the first measure the plank has is taken: compared as they came,
the round-off chose between its two overhangs, and the allowed sag read 0.35 or 1.04 mm
as the design turned."""

UPRIGHT_SINE = 0.5 ** 0.5
"""Above 45 degrees: a beam whose axis rises more than this sine from level is upright
(``validity._upright``: a leg or a side bows, it does not sag), and a sag whose deflection
has a vertical part below it of its size points sideways (``sag._sideways``: a rail
pushed sideways)."""

WINDOW_TOLERANCE = 0.2
"""A geometric repair's window (a gap closed to within the tolerance either side: a board
94 mm up stands on the floor lowered by 93.5 to 94.5 mm), found at the least-squares
step, has its ends closed to this fraction of the design's tolerance in every length DOF
(``suggest.line_search``, ``ranges.nearest``): to 2 % of the step or 0.1 % of the
design's size, an L lowered 49.5 to 50.5 mm read "50 mm only" and 6 .. 6 mm."""

DOF_PARALLEL_EPS = 1e-9
"""A DOF edit takes a direction as lying in a plane below this cosine, and a shift below
this fraction of its step as none (``dofs``: an end along its support cannot follow it)."""

WINDOW_FLOOR = 1e-6
"""m: no window is closed finer than this, whatever the tolerance: with ``tolerance: 0``
a repair's window is a point (a board lowered onto the floor exactly), and a bracket
closed to zero halves for ever once its midpoint rounds to an end."""

STEP_ROUNDOFF = 1e-9
"""A change rounded to the shop's grid counts as within a suggestion's valid steps when
its step is within this fraction of them: the round-off of the steps themselves (a leg
drawn 30 mm short is valid lengthened by the least-squares aim, 0.064794816413834 scaled
units, and 30 mm is the step 0.064794816414687; ``suggest.shop_round``)."""

NEAR_LARGEST = 1e-3
"""A force sensitivity reads a stepped design's planks only at the sample points where the
design's own largest sag (of each measure) and stress may lie: those within this fraction
of the plank's largest, or within NEAR_DESIGN of the design's largest where that is more
(``bending_points.plank_results_where``).  Its steps move every point by about 1e-7 of the
design's largest times the rate's leverage: within either band by far."""

NEAR_DESIGN = 1e-4
"""...of the design's largest sag or stress (``NEAR_LARGEST``): a plank that hardly bends,
its largest sag round-off or nearly, keeps every point, since a step may bend it
anywhere (a wall's middle side between two equal bays; a chair's back, turned)."""

NODE_MERGE = 1e-3
"""m: attachments closer than this along a plank's axis share a node (at their mean, each
held by a rigid arm): a beam element shorter than a millimetre is far stiffer than anything
else and would only cost the solve digits."""

NODE_MERGE_ROUNDOFF = 1e-9
"""m: the round-off spared when attachments' distance along a plank is compared with
NODE_MERGE (and wherever two nodes' distance is, ``statics.bending``, ``_crosswise`` of
``statics.elastic``): designs drawn in whole millimetres put attachments exactly 1 mm
apart, and positions computed from turned planks are off by up to 1e-14 m either way
(bookcase-pins with its shelf turned by 8.6 to 8.8 degrees, a pin's bearing corners 1 mm
+- 7e-15 m from its joint: the pin's stress read 23 or 0.003 N/mm^2 from one hundredth of
a degree to the next, as they shared a node or not).  Attachments drawn 1 mm and a
nanometre apart still get a node each: the rule has an edge, now where no drawing puts
one."""

CONTACT_ITERATIONS = 60
"""Most active-set / friction-anchor iterations per load case."""

SEAT_ROUNDOFF = 1e-9
"""Where a lift leaves a grounded part free to move, a lifted corner whose velocity in
that motion points down by more than this fraction of the fastest corner's is seated
(``contacts._ActiveSet._seat_toppling``); one on the line the part turns about moves
down by round-off only and stays lifted.  And the loads drive no free motion where their
work on the free motions is this fraction of their size or less (their line of action
through that line: ``contacts._free_motion``)."""

FRICTION_CAP_ITERATIONS = 20
"""Most updates of the friction caps mu N from the normal forces in one load case."""

FRICTION_CAP_MEMORY = 3
"""Earlier friction-cap iterates that Anderson's mixing uses besides the last one."""

FRICTION_CAP_STALLS = 2
"""Friction-cap updates in a row that do not beat the least disagreement met so far, after
which the caps are updated by relaxed plain steps (FRICTION_CAP_RELAXATION) instead of
Newton's method or Anderson's mixing, until one beats it (then Newton's method again): a
splayed coffee table's corner at the edge between sticking and slipping sent those round,
its caps alternating between two states, and whether they settled within
FRICTION_CAP_ITERATIONS, or the programs' forces were taken, depended on the design's turn
(a leg joint's force by 6 %)."""

FRICTION_CAP_RELAXATION = 0.7
"""The fraction of the caps' disagreement mu N - c that a relaxed plain update takes (a
Krasnoselskii-Mann step: it damps the two-state cycle that the full one goes round).  On 35
edits of the splayed coffee table, each in two turns, 0.7 after 2 stalls left none of their
friction phases unsettled (5 before, 2 with 0.5) and took the fewest Newton steps of 0.3,
0.5 and 0.7 after 1, 2 or 3 stalls."""

FRICTION_NEWTON_ITERATIONS = 100
"""Most Newton steps when minimizing the energy with slipping friction springs."""

CONTACT_NEWTON_ITERATIONS = 200
"""Most (damped) steps of the semismooth Newton method on the whole contact law
(``statics.newton``), the fallback where the active set and the friction phase cannot
settle: the cycling cases met take 4 to 100."""

BALANCE_ROUNDOFF = 1e-13
"""Relative round-off of a matrix-vector product of the condensed system (a few hundred
terms of double precision), as a fraction of its largest entry times the sum of |x|: a
bound that holds for every row at once (the loose floor of
``statics.friction.balance_floors``)."""

BALANCE_ROW_ROUNDOFF = 1e-14
"""Relative round-off of one row of that product (about 45 units of the last place), as a
fraction of the row's sum of |S0_ij x_j|: the tight floor below which an out-of-balance
force is round-off (``statics.friction.balance_floors``)."""

CONTACT_ROUNDOFF = 2.2e-16
"""Relative round-off of a contact's displacement w = M x (a sum of six products, twelve for
a resting corner), as a fraction of its sum of |M_j x_j|: one unit of the last place
(machine epsilon; a stalled near-mechanism's w was off by 0.1 to 0.2 of it, measured
against extended precision).  Times the contact's spring, the round-off of the force it
computes from w, which ``statics.friction.balance_floors`` adds to its loose floor."""

BALANCE_STALLED = 0.5
"""Between the tight floor and the loose one (a bound of the round-off that holds for every
row at once), a Newton step that does not bring the out-of-balance force under this
fraction of the last one has stalled: the equilibrium is taken as met."""

FULL_STEP_GRADIENT = 0.5
"""A full Newton step of the friction energy is taken, short of the exact line search's
step, where it brings the largest out-of-balance force below this fraction of the least
one met so far in that minimization and the energy still falls at its end (it lets many
contacts change between sticking and slipping, or pressing and lifting, at once; the
record it must beat keeps it from cycling).  Taken even where the energy rose at its end,
it went uphill along the nearly flat valley of a design held at 99 % of its friction,
where the caps balance the push and the out-of-balance force is small however far it
slides: 5 cm, then metres, and the minimization gave up where a minimum lay 0.5 mm from
its start (``tests/test_invariants.py``, the l-shelf at the edge of sliding)."""

RATE_ROUNDOFF = 1e-9
"""A linearized margin's rate is taken as zero (round-off of a rate that is zero by
symmetry) where it changes the margin by less than this fraction of the margin's size (at
least 1) over the DOF's whole search reach; margins as low as each other to this fraction
are tied (``ranges.finder.RangeFinder._favoured_sign``)."""

LINE_SEARCH_ITERATIONS = 30
"""Most iterations of a Newton step's line search between two breakpoints of the slope
along the step, and most doublings of the step beyond the full step (each an O(contacts)
evaluation of the slope in closed form)."""

LINE_SEARCH_SLOPE = 0.1
"""A Newton step's line search stops where the slope along the step is within this
fraction of its slope at the start (the strong Wolfe condition; the elastic catalog's
friction phases took 131 Newton steps in all with it, 140 with 1e-3, 141 with 0.3, when
corners were lifted between minimizations; 214 with it in the Tresca form)."""

LINE_SEARCH_EXTEND = 0.5
"""A Newton step's line search looks beyond the full step only where the slope there is
still steeper than this fraction of its slope at the start (the energy is much flatter
than the Hessian said, as along a sliding motion); where the slope has risen more but is
still < 0, the full step is taken."""

LINE_SEARCH_BRACKET = 1e-12
"""A Newton step's line search also stops where the interval known to hold the slope's
zero is this fraction of its upper end wide (the slope's round-off is then larger than
what is left to find)."""

SLIP_STIFFNESS = 1e-10
"""A slipping contact's stiffness along its slip in a Newton step, relative to the contact
stiffness (its true stiffness there is zero): keeps the step finite where the whole design
could slide freely, as a shift of SOLVE_RESIDUAL would (1 N/m in the elastic model)."""

ASSEMBLY_STEP = 1e-4
"""Step of the central difference of the assembly behind the force sensitivity (paper eq.
6), as a fraction of the design's size (lengths) or in degrees (rotations), in the rigid
model.  Where the assembly is smooth this is exact to ~1e-8.  Where it has a kink -- a
flush end face that a rotation tilts rests on one edge or the other depending on the sign
of the turn -- the derivative is the mean of the two one-sided slopes; ranges do not rely
on it beyond a first guess (every end is confirmed by the full check)."""

ELASTIC_ASSEMBLY_STEP = 1e-7
"""The same step for lengths in the elastic model.  Its assembly bends on the scale of its
shortest beam elements (a joint half a thickness from a plank's end: element stiffness
goes as 1 / L^3), so the truncation of a central difference is about (h / L)^2: 1e-3 of
the derivative at 1e-4 (table top.length), 1e-7 at 1e-7; round-off shows below 1e-9 (the
contact springs' stiff terms cancel in b - A x)."""

ELASTIC_ANGLE_STEP = 1e-5
"""Degrees: the elastic model's step for rotations, moving a plank's far end by about as
much as ELASTIC_ASSEMBLY_STEP moves a length (smaller turns are lost in the round-off of
the rotated geometry)."""

SLIP_DETECTION = 1e-9
"""A solved contact counts as slipping (for the sensitivity's contact law) where its
tangential force falls short of k |w_t| by more than this fraction: a sticking contact's
force is -k w to round-off."""

SLIDING_DISPLACEMENT = 10.0
"""m: a contact-spring displacement this large means the energy falls without bound: the
loads exceed what friction can hold (springs deflect ~1e-3 m under real loads).  A
linear solve of a contact state whose grounded planks' displacements (metres, and
radians for their turns) pass it is a mechanism regular only by round-off
(``contacts._ActiveSet.solve``).  Measured as the longest translation or rotation vector
of a grounded node (``friction.displacement_size``), the same in every turn of the
design."""

FORCE_REL_TOL = 1e-9
"""Relative force slack (of the total applied load) for contact sign and cone checks."""

FRICTION_CONE_SIDES = 64
"""Sides of the polygonal friction pyramids of the sliding feasibility program.  They are
inscribed in the Coulomb cones, so a 'sliding' verdict from them is conservative by at
most 1 - cos(pi / 64) = 0.12 % of the friction (the circumscribed pyramid, mu / cos(pi /
64), would bound it from the other side)."""

PUSH_ROUNDOFF = 1e-9
"""A load's or an elastic contact force's sideways part (in a contact's plane) smaller than
this fraction of it is round-off: it gives the friction pyramids of the admissible forces
closest to the elastic ones no direction (``feasibility._pushed``, ``_admissible_edges``)."""

EQUILIBRIUM_WEIGHT = 1e6
"""Weight of the equilibrium rows against the distance to the elastic forces when the
admissible contact forces closest to them are sought (``feasibility.closest_admissible``):
the equilibrium then holds to about 1e-12 of that distance."""

SOLVE_RESIDUAL = 1e-10
"""Largest accepted normwise backward error of a linear solve (residual over
|A| |x| + |b|); larger means a singular or badly pivoted system."""

DENSE_PLANKS_MAX = 360
"""Designs with at most this many plank displacements (6 per plank, i.e. up to 60
planks) are condensed through the planks with a dense joint stiffness matrix
(``statics.condense._PlankCondensation``); larger ones through the sparse mixed system."""

CONDENSED_DENSE_BYTES = 32 * 2 ** 20
"""Largest dense X = A_ii^-1 A_ig (bytes) that a condensation keeps (the catalog's take a
few MB); a larger one (a 2,000-plank wall's: 47,580 x 246, 94 MB, and as much again for
A_ig made dense) is never stored: S0 is summed a block of its columns at a time and
X x_g solved for when needed (``statics.condense._implicit``)."""

TRAILING_SCHUR_MAX = 1500
"""A large elastic condensation's S0 is read from the trailing block of one more sparse LU
when it has at most this many grounded unknowns (250 nodes; a 2,001-plank wall's 41
sides: 246), else summed from one solve per unknown (``statics.condense._trailing_schur``):
the trailing factors are dense, about 12 n^2 bytes each besides S0 (27 MB at this size)."""

SENSITIVITY_BLOCK_BYTES = 32 * 2 ** 20
"""The force sensitivity (eq. 6) solves its DOFs' right-hand sides a block at a time, at
most this many bytes of them (the catalog's designs: all DOFs in one block; a 2,000-plank
wall's 71,346 unknowns: 58 DOFs a block), so that no dense all-DOF x all-unknown matrix is
made (``sensitivity.Linearization.derivatives``)."""

PLANK_BATCH = 4096
"""Most planks whose sag and stress are read in one stacked pass of the sensitivity
(``bending.plank_results_many``: about 30 kB of temporaries per plank; 224 DOFs of the
28-plank cabinet are 6,272 planks)."""

ANCHORED_CACHE_BYTES = 256 * 2 ** 20
"""Most bytes of factored contact-state matrices a statics model keeps for its next
solves (``statics.anchored.anchored_system``; the least recently used go first): all
of them for the catalog's designs (a few kB each), one or two of a design standing on
600 planks (2 x 104 MB each)."""

MAX_MEETING_PAIRS = 200_000
"""Most plank pairs whose boxes meet (``geometry.boxes.meeting_pairs``) that the geometry
compares face by face, about 2 kB each: furniture has a few per plank (the 28-plank
cabinet 99, a 20,000-board stack 19,999), but planks drawn on top of one another meet
in n^2 / 2 (2,000 boards in one place: 2 million pairs, 4.2 GB and 30 s before the
contact system was refused; 500 of them, 125,000 pairs, 330 MB).  A design with more is
refused (``errors.DesignTooBig``, ``check.refuse_overlapping``) as it is read, before
they are compared."""

MAX_GROUND_UNKNOWNS = 3600
"""Most unknowns of a design's dense contact system (six per node a ground contact sits
on: 600 planks standing on the floor).  Its condensed matrix, the factors of its contact
states and the friction phase's contact maps are dense, 8 n^2 bytes each (104 MB at this
size), so memory grows with the square of the planks on the floor.  A design with more is
refused before anything is solved (``check.refuse_too_big``).  Measured on rows of sides
standing on the floor (a shelf nailed between each two, one loaded to sag): 600 sides
(3,600 unknowns) take 650 MB to validate and 1.10 GB to suggest; 1,001 sides 1.56 GB to
validate."""

SUGGEST_ALL_PLANKS = 128
"""``suggest`` considers every DOF of a design with at most this many planks (1,024 DOFs;
the catalog's and the paper's designs have at most 28); in a larger one only the DOFs of
the SUGGEST_NEAR_PLANKS planks nearest its violations (``neighbourhood``)."""

SUGGEST_NEAR_PLANKS = 12
"""Planks whose DOFs a big design's suggestions may change (``neighbourhood``): the ones
its violations name and those nearest them (96 DOFs)."""

SENSITIVITY_ALL_PLANKS = 128
"""The force sensitivity of an elastic model of at most this many planks reads every
plank's sag and stress rate; of a larger one only those of the planks its DOFs change and
of the planks jointed to them (``sensitivity.Linearization._planks_read``): reading a
plank costs about 0.25 ms per DOF, all 2,000 of a shelving wall half a second."""

MECHANISM_RCOND = 1e-10
"""Smallest singular value (relative) of a component's ground-support stiffness below
which the component is a mechanism (free to move)."""

# --- validity -----------------------------------------------------------------------------
CAPACITY_REL_TOL = 1e-9
"""A nail force within this relative slack of its capacity counts as durable."""

# --- suggestions: the cut list and the shop's score ---------------------------------------
CUT_LIST_EPS = 1e-6
"""A plank's field counts as changed by a suggestion when it moves by more than this, in
its own unit (the file's length unit, degrees, or the material key's unit): far below a
saw's kerf, far above the round-off of writing a design file back (12 digits)."""

STOCK_BOARD = (2.440, 1.220)
"""m: the largest board a plank is cut from, length x width: the standard full sheet of
MDF, 2440 x 1220 mm (8 x 4 ft; EN 622-5 boards and the sheet sizes of MDF makers). A
suggestion that makes a plank too big to cut from one sheet, when it was not, is
implausible (``suggest.score``)."""

MIRROR_TOLERANCE_FACTOR = 1.0
"""Two planks are mirror images of each other when every mirrored corner of one lies
within this many times the design's tolerance of a corner of the other
(``suggest.symmetry``)."""

# --- output -------------------------------------------------------------------------------
REPORT_SIGNIFICANT_DIGITS = 6
"""Floats in reports are rounded to this many significant digits (deterministic output)."""
REPORT_DECIMALS = 6
"""...after rounding to this many decimals (of N, N m, the file's length unit), so solver
round-off such as 2e-14 mm or 1e-16 N is written as 0."""

# --- design files: input limits and range guards (loader; SI unless the name says) ------
MAX_FILE_BYTES = 5 * 1024 * 1024
"""Largest design file read (5 MiB, 5,242,880 bytes); a catalog's furniture is a few kB."""
MAX_NESTING = 32
"""Deepest nesting of mappings and lists in a design file (a valid one needs 5)."""
MIN_LENGTH = 1e-5                # m: smallest plank size, thickness, nail spacing
MAX_LENGTH = 1e3                 # m: largest plank size, thickness, nail spacing, tolerance
MAX_COORDINATE = 1e3             # m: largest |coordinate| of a centre or load point
MAX_MASS = 1e7                   # kg per load
MAX_FORCE = 1e9                  # N, largest |component| of a load force
MAX_DENSITY = 1e5                # kg/m^3
MAX_FRICTION = 10.0              # static Coulomb coefficient
MIN_SAFETY_FACTOR = 1e-3
MAX_SAFETY_FACTOR = 1e3
MAX_NAIL_CAPACITY = 1e7          # N per nail, pull or shear
MAX_MODULUS = 1e13               # Pa: elastic and shear modulus, bending strength
MAX_CREEP = 100.0
MAX_SAG_LIMIT = 1e6
MAX_NAIL_STIFFNESS = 1e13        # N/m per nail, slip or withdrawal
MAX_ROTATION_DEG = 1e4           # degrees, largest |rotation| about one axis
MAX_NAILS = 1e6                  # nails of one listed joint
ANCHOR_STIFFNESS = 4.5e6
"""N/m: an anchor's spring in the elastic model, in each of its three directions: the
slip modulus of a screw joint, EN 1995-1-1 Table 7.1, K_ser = rho_m^1.5 d / 23 per shear
plane, for a 5 mm screw in MDF (rho_m = 750 kg/m^3): 4.47 kN/mm; its withdrawal taken as
stiff.  Far softer than a ground contact (ELASTIC_CONTACT_STIFFNESS): a wall's anchors
hold what the planks' bending leaves them, and do not clamp a cleat's face against its
own bending (as rigid ties would: a 600 mm cleat under a 30 kg shelf then pulled its two
screws apart with 2 kN each).  In the rigid model the anchors' springs are the contacts'
penalty springs (CONTACT_STIFFNESS)."""
ANCHOR_CAP = 1e30
"""N: the friction cap that the contact iterations give an anchor's tie, which never slips
(a force no load reaches; finite, so that the friction phase's arithmetic stays finite)."""
WALL_NORMAL_TILT = 1e-6
"""Largest |z| of a wall's normal, relative to its length: walls are vertical (contract
section 2); a normal within this of horizontal is made exactly horizontal."""
ON_PLANK_EPS = 1e-9
"""m: round-off slack (on top of the design's tolerance) when a load point is checked to
lie on its plank, so a point exactly on a face is on the plank even with tolerance 0."""

# --- suggest ----------------------------------------------------------------------------
MAX_COMBINED_DOFS = 4
"""The most DOFs one continuous suggestion may change together (``suggest --max-dofs``).
Directions are formed for every combination of up to M of the DOFs that move the violated
margins (at most 48 of them, ``suggest.candidates``): C(48, 4) = 194,580 combinations take
12 s on the 37-plank bookshelf-20 in the elastic model, C(48, 5) = 1.7 million took over
150 s, C(48, 6) = 12 million would take about 20 minutes; and on the catalog no design got
a suggestion from 5 or 6 DOFs that 4 did not give (README, "How do I fix it?")."""
# --- discrete suggestions (furncheck.suggest.discrete) -----------------------------------
STOCK_THICKNESSES = (0.012, 0.015, 0.018, 0.022, 0.025, 0.030, 0.036, 0.044)
"""m: board thicknesses a thicker plank is chosen from: the MDF and plywood sheets sold
in 12 to 30 mm, and two 18 or 22 mm sheets glued face to face (36, 44 mm)."""
STOCK_MATCH = 1e-6
"""Relative slack when a needed thickness is matched to a board (12.000000001 mm is a 12 mm
board)."""
ANCHOR_CAPACITY = 196.0
"""N: the rating of a wall anchor that ``suggest`` proposes: one plasterboard fixing's safe
static load in tension, 20 kg (Gripit red, data sheet GR0049 UK, 2018; the catalog's
``bookcase-anchored`` uses it too)."""
WALL_ANCHOR_REACH = 0.05
"""m: a plank whose nearest corner stands at most this far in front of a wall can be
anchored to it (a bracket or a packing piece bridges the gap)."""

PUSH_ANGLE = 1.0
"""Degrees: a loose part's resting corners push it one way (``geometry.loose``) when each
one's push lies within this of their mean (a board under a block tilted by a hundredth of
a degree, well within the tolerance, is still one support plane)."""

HOLD_TIE = 1e-9
"""Hull points whose hold-down is within this share of the least (round-off) are named
with it: a sawhorse's two far feet, a loose top's two back corners."""

ROOM_SLACK = 1e-9
"""Share by which a joint's needed length (``suggest.needs``) may pass what its planks
have room for along its line (round-off) before the estimate says they have none."""

ANCHOR_PART = 0.01
"""Share of an anchor's force below which its message leaves a part of it out (its pull
out of the wall, what it holds up, its shear along the wall)."""

WALL_FRICTION_SHARE = 0.05
"""Share of what a design's supports hold up (its weight and loads) from which a valid
anchored design's summary says how much of it the wall's friction holds ('with the
wall's friction holding up 118 N of its 178 N of weight and loads'): the anchors'
utilization then counts on that friction, which a fixing's rated shear may be meant to
carry alone."""

