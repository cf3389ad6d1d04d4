#!/usr/bin/env python3
"""Generate a lathe machine model: models/lathe-<variant>/{machine.urdf,README.md,meshes/*.ply}.

Variants (same bed, carriage, cross slide, turret and tailstock):
  c1  main spindle driven by motor S1 through a belt; C-axis servo geared onto the spindle
      through a dog clutch (C-axis manual 3: rotary axis mode using a separate servo drive)
  c2  main spindle driven directly by a frameless motor whose drive is also the C axis (C-axis
      manual 2: main spindle drive with rotary axis capability): no belt, no servo, no clutch

Python 3 standard library only. The output is deterministic (same bytes on every run): all
numbers are written with fixed formatting, all lists are emitted in a fixed order.

Conventions (see models/lathe-c1/README.md, which this script also writes):
  world frame = `bed` link frame; x radial (machine X, toward the turret at the back), y up,
  z along the spindle axis (machine Z, toward the tailstock); origin on the spindle axis in the
  plane of the headstock face. Metres, radians, kilograms.

Every mesh file is one closed, consistently wound (outward) solid, written in its link's frame,
with per-vertex normals; every mesh that is also used as collision geometry is one convex solid.
Run:  python3 tools/gen_lathe_model.py [--variant c1|c2] [-q]
"""

import argparse
import math
import os

from lathe_geometry import (SEG_SMALL, Frame, Mesh, axis_frame, composite, cross, deg, f6,
                            fnum, fvec, rotz)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

TOOL_R = 0.18    # tool tips: radius from the turret axis, at z = 0 of the turret frame
# lathe-c1's second stylus points along -z (toward the headstock): it reaches what the radial
# one in station 3 cannot, the floor and the walls of a face groove. Station 7 has empty
# neighbours, so nothing beside it reaches toward the part.
AXIAL_PROBE_STATION = 7
AXIAL_PROBE_REACH = 0.05   # ruby centre ahead of the tool-tip plane, along -z
DISC_R = 0.13    # turret disc circumradius (12-sided)


# ------------------------------------------------------------------------------------ materials
MATERIALS = [
    ("bed_blue", (0.20, 0.25, 0.31, 1.0)),        # bed, headstock, housings: dark grey-blue
    ("rail_steel", (0.56, 0.58, 0.61, 1.0)),      # ground guideways
    ("bolt_dark", (0.14, 0.15, 0.16, 1.0)),
    ("carriage_grey", (0.60, 0.63, 0.66, 1.0)),   # saddle and cross slide: lighter grey
    ("chuck_steel", (0.62, 0.64, 0.66, 1.0)),
    ("jaw_dark", (0.27, 0.28, 0.30, 1.0)),
    ("marker_orange", (1.00, 0.45, 0.00, 1.0)),   # rotation markers
    ("turret_grey", (0.80, 0.81, 0.82, 1.0)),
    ("holder_dark", (0.17, 0.18, 0.20, 1.0)),     # tool holders and shanks
    ("insert_gold", (0.88, 0.70, 0.12, 1.0)),     # coated inserts
    ("tool_carbide", (0.70, 0.71, 0.74, 1.0)),    # drills, end mills
    ("probe_white", (0.93, 0.93, 0.91, 1.0)),
    ("probe_red", (0.82, 0.08, 0.08, 1.0)),
    ("stylus_steel", (0.75, 0.76, 0.78, 1.0)),
    ("ruby", (0.70, 0.00, 0.09, 1.0)),
    ("tailstock_grey", (0.47, 0.50, 0.53, 1.0)),
    ("motor_black", (0.06, 0.06, 0.07, 1.0)),
    ("motor_cap_blue", (0.05, 0.38, 0.72, 1.0)),  # S1 motor end cap
    ("motor_cap_green", (0.10, 0.60, 0.30, 1.0)), # C servo end cap
    ("pulley_alu", (0.78, 0.79, 0.80, 1.0)),
]


# ------------------------------------------------------------------------------------ the model
def station_angle(k):
    """Turret-frame angle of station k (1..12), from +x toward +y. With turret joint angle
    (k-1)*30 deg station k points along world -x, toward the spindle."""
    return deg(180.0 - (k - 1) * 30.0)


def build_c1_motors(part, link):
    """lathe-c1's spindle motor S1 (belt to the spindle) and C-axis servo (clutch K)."""
    # ----------------------------------------------------------------------------- s1_motor
    P = []
    part("s1_motor_cap").cylinder(0.09, -0.15, -0.12)
    P.append(("s1_motor_cap", "s1_motor_cap", "motor_cap_blue", True))
    part("s1_motor_body").cylinder(0.09, -0.12, 0.15)
    P.append(("s1_motor_body", "s1_motor_body", "motor_black", True))
    part("s1_motor_pulley").cylinder(0.06, 0.15, 0.19)
    P.append(("s1_motor_pulley", "s1_motor_pulley", "pulley_alu", True))
    part("s1_motor_key").box(0.045, 0.0615, -0.006, 0.006, 0.17, 0.1915)
    P.append(("s1_motor_key", "s1_motor_key", "marker_orange", False))
    link("s1_motor", composite(30.0, [("cylz", 0.0, 0.0, 0.09, -0.15, 0.15),
                                      ("cylz", 0.0, 0.0, 0.06, 0.15, 0.19)], izz=0.05), P)

    # ------------------------------------------------------------------------------ c_motor
    P = []
    part("c_motor_cap").cylinder(0.06, -0.11, -0.08)
    P.append(("c_motor_cap", "c_motor_cap", "motor_cap_green", True))
    part("c_motor_body").cylinder(0.06, -0.08, 0.11)
    P.append(("c_motor_body", "c_motor_body", "motor_black", True))
    part("c_motor_pinion").cylinder(0.03, 0.11, 0.15)
    P.append(("c_motor_pinion", "c_motor_pinion", "pulley_alu", True))
    part("c_motor_key").box(0.02, 0.0315, -0.004, 0.004, 0.13, 0.1515)
    P.append(("c_motor_key", "c_motor_key", "marker_orange", False))
    link("c_motor", composite(12.0, [("cylz", 0.0, 0.0, 0.06, -0.11, 0.11),
                                     ("cylz", 0.0, 0.0, 0.03, 0.11, 0.15)], izz=0.003), P)


def build(variant):
    """Returns (links, joints, meshes, stations) of variant c1 or c2. A link is a dict with
    name, inertial, parts; a part is (name, mesh name, material, collide)."""
    meshes = {}
    links = []

    def part(mesh_name):
        m = Mesh(mesh_name)
        if mesh_name in meshes:
            raise SystemExit("duplicate mesh " + mesh_name)
        meshes[mesh_name] = m
        return m

    def link(name, inertial, parts):
        links.append({"name": name, "inertial": inertial, "parts": parts})

    # ---------------------------------------------------------------------------------- bed
    P = []
    part("bed_base").box(-0.35, 0.60, -0.60, -0.40, -0.55, 1.05)
    P.append(("bed_base", "bed_base", "bed_blue", True))
    part("bed_headstock").box(-0.20, 0.20, -0.40, 0.22, -0.50, -0.02)
    P.append(("bed_headstock", "bed_headstock", "bed_blue", True))
    part("bed_carriage_rail").box(0.15, 0.55, -0.40, -0.34, -0.02, 1.0)
    P.append(("bed_carriage_rail", "bed_carriage_rail", "rail_steel", True))
    part("bed_tailstock_rail").box(-0.15, 0.10, -0.40, -0.36, 0.10, 1.0)
    P.append(("bed_tailstock_rail", "bed_tailstock_rail", "rail_steel", True))
    # spindle bearing cap on the headstock face, around the spindle nose
    part("bed_nose_ring").cylinder(0.13, -0.02, -0.006)
    P.append(("bed_nose_ring", "bed_nose_ring", "bed_blue", True))
    # motor brackets (the motors are links of their own; 2 mm clearance below them)
    if variant == "c1":
        part("bed_s1_mount").box(0.26, 0.38, -0.40, -0.272, -0.46, -0.24)
        P.append(("bed_s1_mount", "bed_s1_mount", "bed_blue", True))
        part("bed_c_mount").box(-0.34, -0.26, -0.40, -0.212, -0.44, -0.26)
        P.append(("bed_c_mount", "bed_c_mount", "bed_blue", True))
    else:
        # the frameless motor's stator sits in the headstock; its end cover shows at the back
        part("bed_stator_cover").cylinder(0.14, -0.56, -0.50)
        P.append(("bed_stator_cover", "bed_stator_cover", "motor_cap_blue", True))
    bolts = part("bed_bolts")    # hex bolt heads on the headstock face (visual only)
    for bx, by in ((-0.17, 0.19), (0.17, 0.19), (-0.17, -0.37), (0.17, -0.37),
                   (-0.17, -0.09), (0.17, -0.09)):
        bolts.ngon_prism(6, 0.012, -0.02, -0.011, Frame((bx, by, 0.0)))
    P.append(("bed_bolts", "bed_bolts", "bolt_dark", False))
    link("bed", composite(2500.0, [
        ("box", -0.35, 0.60, -0.60, -0.40, -0.55, 1.05),
        ("box", -0.20, 0.20, -0.40, 0.22, -0.50, -0.02),
        ("box", 0.15, 0.55, -0.40, -0.34, -0.02, 1.0),
        ("box", -0.15, 0.10, -0.40, -0.36, 0.10, 1.0)]), P)

    # ------------------------------------------------------------------------------ spindle
    P = []
    part("spindle_shaft").cylinder(0.07, -0.012, 0.0)   # visible in the gap to the bearing cap
    P.append(("spindle_shaft", "spindle_shaft", "chuck_steel", False))
    part("spindle_flange").cylinder(0.11, 0.0, 0.02)
    P.append(("spindle_flange", "spindle_flange", "chuck_steel", True))
    part("spindle_chuck_body").cylinder(0.105, 0.02, 0.10)
    P.append(("spindle_chuck_body", "spindle_chuck_body", "chuck_steel", True))
    for i, a in enumerate((0.0, 120.0, 240.0)):
        name = "spindle_jaw%d" % (i + 1)
        part(name).box(0.032, 0.085, -0.0125, 0.0125, 0.10, 0.14, rotz(deg(a)))
        P.append((name, name, "jaw_dark", True))
    # rotation marker on the chuck rim, between jaws 1 and 2 (at +60 deg)
    part("spindle_marker").box(0.094, 0.1065, -0.009, 0.009, 0.06, 0.1025, rotz(deg(60.0)))
    P.append(("spindle_marker", "spindle_marker", "marker_orange", False))
    jaw_parts = [("box", 0.0585 * math.cos(deg(a)) - 0.02, 0.0585 * math.cos(deg(a)) + 0.02,
                  0.0585 * math.sin(deg(a)) - 0.02, 0.0585 * math.sin(deg(a)) + 0.02, 0.10, 0.14)
                 for a in (0.0, 120.0, 240.0)]
    spindle_parts = [("cylz", 0.0, 0.0, 0.11, 0.0, 0.02),
                     ("cylz", 0.0, 0.0, 0.105, 0.02, 0.10)] + jaw_parts
    if variant == "c1":
        link("spindle", composite(45.0, spindle_parts, izz=0.25), P)
    else:
        # c2: the frameless motor's rotor sits on the spindle shaft inside the headstock
        # (hidden, so no mesh): 15 kg more, Izz 0.25 + 0.07 kg m^2.
        link("spindle", composite(60.0, spindle_parts + [("cylz", 0.0, 0.0, 0.07, -0.45, -0.012)],
                                  izz=0.32), P)
    if variant == "c1":
        build_c1_motors(part, link)
    # ---------------------------------------------------------------------------- z_carriage
    P = []
    part("z_carriage_saddle").box(0.14, 0.56, -0.34, -0.22, 0.02, 0.40)
    P.append(("z_carriage_saddle", "z_carriage_saddle", "carriage_grey", True))
    link("z_carriage", composite(120.0, [("box", 0.14, 0.56, -0.34, -0.22, 0.02, 0.40)]), P)

    # ------------------------------------------------------------------------------ x_slide
    P = []
    part("x_slide_cross_slide").box(0.30, 0.56, -0.22, -0.12, 0.04, 0.38)
    P.append(("x_slide_cross_slide", "x_slide_cross_slide", "carriage_grey", True))
    part("x_slide_turret_housing").box(0.24, 0.42, -0.12, 0.10, 0.12, 0.36)
    P.append(("x_slide_turret_housing", "x_slide_turret_housing", "bed_blue", True))
    # bearing boss of the turret axis: the housing box does not reach the axis (x = 0.18)
    part("x_slide_turret_boss").cylinder(0.10, 0.092, 0.24, Frame((0.18, 0.0, 0.0)))
    P.append(("x_slide_turret_boss", "x_slide_turret_boss", "bed_blue", True))
    link("x_slide", composite(80.0, [("box", 0.30, 0.56, -0.22, -0.12, 0.04, 0.38),
                                     ("box", 0.24, 0.42, -0.12, 0.10, 0.12, 0.36),
                                     ("cylz", 0.18, 0.0, 0.10, 0.092, 0.24)]), P)

    # ------------------------------------------------------------------------------- turret
    P = []
    # 12-sided disc, faces centred on the station rays (vertices at 15 + 30 m degrees)
    part("turret_disc").ngon_prism(12, DISC_R, -0.03, 0.03, phase=deg(15.0))
    P.append(("turret_disc", "turret_disc", "turret_grey", True))
    part("turret_hub").cylinder(0.06, 0.03, 0.034)        # bridges the gap to the boss
    P.append(("turret_hub", "turret_hub", "turret_grey", False))
    stations = []
    for k in range(1, 13):
        phi = station_angle(k)
        fr = rotz(phi)                           # local x = station ray, y = tangential, z = z
        hname = "turret_st%02d_holder" % k
        if k == 3 or (k == AXIAL_PROBE_STATION and variant == "c1"):  # probe adapter plate
            part(hname).box(0.12, 0.13, -0.025, 0.025, -0.028, 0.028, fr)
        elif k == 4:    # driven tool housing
            hname = "turret_st04_housing"
            part(hname).box(0.115, 0.14, -0.032, 0.032, -0.03, 0.03, fr)
        else:
            part(hname).box(0.12, 0.155, -0.025, 0.025, -0.028, 0.028, fr)
        P.append((hname, hname, "holder_dark", True))
        tool = "empty"
        if k == 1:
            tool = "turning tool (80 deg rhombic insert, CNMG-like)"
            part("turret_st01_shank").box(0.13, 0.172, -0.0125, 0.0125, -0.0025, 0.0225, fr)
            P.append(("turret_st01_shank", "turret_st01_shank", "holder_dark", True))
            # insert in the plane (ray, z), thickness 5 mm along the tangential direction.
            # Cutting corner (80 deg) exactly at r = 0.18, z = 0; main edge 5 deg off the ray
            # (95 deg approach), trailing edge nearly along +z (toward the tailstock).
            L = 0.0129
            e1 = (math.cos(deg(175.0)), math.sin(deg(175.0)))
            e2 = (math.cos(deg(95.0)), math.sin(deg(95.0)))
            rh = [(TOOL_R, 0.0), (TOOL_R + L * e1[0], L * e1[1]),
                  (TOOL_R + L * (e1[0] + e2[0]), L * (e1[1] + e2[1])),
                  (TOOL_R + L * e2[0], L * e2[1])]
            d = fr.ex
            ins_frame = Frame((0.0, 0.0, 0.0), d, (0.0, 0.0, 1.0), cross(d, (0.0, 0.0, 1.0)))
            part("turret_st01_insert").prism(rh, -0.0025, 0.0025, ins_frame)
            P.append(("turret_st01_insert", "turret_st01_insert", "insert_gold", True))
        elif k == 2:
            tool = "grooving tool (3 mm blade)"
            part("turret_st02_blade").box(0.13, 0.172, -0.012, 0.012, -0.0015, 0.0015, fr)
            P.append(("turret_st02_blade", "turret_st02_blade", "holder_dark", True))
            part("turret_st02_tip").box(0.172, TOOL_R, -0.004, 0.004, -0.0015, 0.0015, fr)
            P.append(("turret_st02_tip", "turret_st02_tip", "insert_gold", True))
        elif k == 3:
            tool = "touch probe (link probe, fixed joint probe_mount)"
        elif k == AXIAL_PROBE_STATION and variant == "c1":
            tool = "axial touch probe (link probe_axial, fixed joint probe_axial_mount)"
        elif k == 4:
            tool = "driven tool S2 (link s2_spindle, end mill d10)"
        elif k == 5:
            tool = "drill d12 (radial)"
            part("turret_st05_collet").cylinder(0.014, 0.155, 0.165, axis_frame((0, 0, 0),
                                                                                   fr.ex))
            P.append(("turret_st05_collet", "turret_st05_collet", "holder_dark", True))
            drill = part("turret_st05_drill")
            r_d = 0.006
            h_pt = r_d / math.tan(deg(59.0))               # 118 deg point
            af = axis_frame((0, 0, 0), fr.ex)
            drill.frustum(r_d, r_d, 0.15, TOOL_R - h_pt, SEG_SMALL, af, cap0=True, cap1=False)
            drill.frustum(r_d, 0.0, TOOL_R - h_pt, TOOL_R, SEG_SMALL, af, cap0=False)
            P.append(("turret_st05_drill", "turret_st05_drill", "tool_carbide", True))
        tip = (TOOL_R * math.cos(phi), TOOL_R * math.sin(phi), 0.0)
        stations.append((k, 180 - (k - 1) * 30, tip, tool))
    holders = [("cylz", 0.0, 0.0, DISC_R * math.cos(deg(15)), -0.03, 0.03)]
    for k in range(1, 13):
        c = (0.1375 * math.cos(station_angle(k)), 0.1375 * math.sin(station_angle(k)))
        holders.append(("box", c[0] - 0.02, c[0] + 0.02, c[1] - 0.02, c[1] + 0.02,
                        -0.028, 0.028))
    link("turret", composite(60.0, holders, izz=0.6), P)

    # -------------------------------------------------------------------------------- probe
    P = []
    ax = Frame((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0))  # z := +x
    part("probe_body").cylinder(0.02, 0.0, 0.024, ax)
    P.append(("probe_body", "probe_body", "probe_white", True))
    part("probe_band").cylinder(0.02, 0.024, 0.03, ax)
    P.append(("probe_band", "probe_band", "probe_red", True))
    part("probe_stylus").cylinder(0.002, 0.03, 0.047, ax)
    P.append(("probe_stylus", "probe_stylus", "stylus_steel", True))
    part("probe_ruby").sphere((0.047, 0.0, 0.0), 0.003)
    P.append(("probe_ruby", "probe_ruby", "ruby", True))
    link("probe", composite(0.3, [("cylx", 0.0, 0.0, 0.02, 0.0, 0.03),
                                  ("cylx", 0.0, 0.0, 0.002, 0.03, 0.047)]), P)

    # -------------------------------------------------------------------------- probe_axial
    if variant == "c1":
        # The same head as station 3's on an arm that ends where the ray reaches the tool-tip
        # radius, the stylus bent down along -z from there: the ruby is the part nearest the
        # spindle axis, so it enters a face groove with only the stylus above it.
        P = []
        part("probe_axial_body").cylinder(0.02, 0.0, 0.024, ax)
        P.append(("probe_axial_body", "probe_axial_body", "probe_white", True))
        part("probe_axial_band").cylinder(0.02, 0.024, 0.03, ax)
        P.append(("probe_axial_band", "probe_axial_band", "probe_red", True))
        part("probe_axial_arm").cylinder(0.004, 0.03, 0.05, ax)
        P.append(("probe_axial_arm", "probe_axial_arm", "stylus_steel", True))
        part("probe_axial_stylus").cylinder(0.002, -AXIAL_PROBE_REACH + 0.003, 0.0,
                                            Frame((0.047, 0.0, 0.0)))
        P.append(("probe_axial_stylus", "probe_axial_stylus", "stylus_steel", True))
        part("probe_axial_ruby").sphere((0.047, 0.0, -AXIAL_PROBE_REACH), 0.003)
        P.append(("probe_axial_ruby", "probe_axial_ruby", "ruby", True))
        link("probe_axial", composite(0.3, [("cylx", 0.0, 0.0, 0.02, 0.0, 0.03),
                                            ("cylx", 0.0, 0.0, 0.004, 0.03, 0.05),
                                            ("cylz", 0.047, 0.0, 0.002, -0.047, 0.0)]), P)

    # --------------------------------------------------------------------------- s2_spindle
    P = []
    part("s2_spindle_collet").cylinder(0.012, 0.0, 0.02)
    P.append(("s2_spindle_collet", "s2_spindle_collet", "holder_dark", True))
    part("s2_spindle_mill").cylinder(0.005, 0.02, 0.04)
    P.append(("s2_spindle_mill", "s2_spindle_mill", "tool_carbide", True))
    fl = part("s2_spindle_flutes")     # two flute stripes across the cutter (visual only)
    fl.box(-0.0052, 0.0052, -0.0007, 0.0007, 0.022, 0.0395)
    P.append(("s2_spindle_flutes", "s2_spindle_flutes", "holder_dark", False))
    part("s2_spindle_marker").box(0.0110, 0.0135, -0.003, 0.003, 0.004, 0.016)
    P.append(("s2_spindle_marker", "s2_spindle_marker", "marker_orange", False))
    link("s2_spindle", composite(1.0, [("cylz", 0.0, 0.0, 0.012, 0.0, 0.02),
                                       ("cylz", 0.0, 0.0, 0.005, 0.02, 0.04)]), P)

    # ---------------------------------------------------------------------------- tailstock
    P = []
    part("tailstock_body").box(-0.13, 0.09, -0.36, -0.05, 0.12, 0.40)
    P.append(("tailstock_body", "tailstock_body", "tailstock_grey", True))
    # quill housing on the body: the body box stays below the centre height (y <= -0.05)
    part("tailstock_head").cylinder(0.065, 0.12, 0.36)
    P.append(("tailstock_head", "tailstock_head", "tailstock_grey", True))
    part("tailstock_quill").cylinder(0.035, 0.04, 0.14)
    P.append(("tailstock_quill", "tailstock_quill", "chuck_steel", True))
    part("tailstock_centre").frustum(0.0, 0.03, 0.0, 0.04, SEG_SMALL)
    P.append(("tailstock_centre", "tailstock_centre", "chuck_steel", True))
    part("tailstock_handwheel_shaft").cylinder(0.012, 0.36, 0.40)
    P.append(("tailstock_handwheel_shaft", "tailstock_handwheel_shaft", "bolt_dark", True))
    part("tailstock_handwheel").cylinder(0.05, 0.40, 0.415)
    P.append(("tailstock_handwheel", "tailstock_handwheel", "bolt_dark", True))
    link("tailstock", composite(90.0, [("box", -0.13, 0.09, -0.36, -0.05, 0.12, 0.40),
                                       ("cylz", 0.0, 0.0, 0.065, 0.12, 0.36),
                                       ("cylz", 0.0, 0.0, 0.035, 0.04, 0.14)]), P)

    # ------------------------------------------------------------------------------- joints
    # (name, type, parent, child, xyz, rpy, axis, limit dict or None, damping, friction)
    # s2_spindle: rpy (-90 deg, 0, phi4 - 90 deg) turns the child's +z onto station 4's ray
    # (avoids the pitch = 90 deg gimbal-lock form of the same rotation).
    phi3, phi4 = station_angle(3), station_angle(4)
    phi_axial = station_angle(AXIAL_PROBE_STATION)
    joints = [
        ("spindle", "continuous", "bed", "spindle", (0, 0, 0), (0, 0, 0), (0, 0, 1),
         {"effort": 500, "velocity": 630}, 0.01, 0.5),
        ("s1_motor", "continuous", "bed", "s1_motor", (0.32, -0.18, -0.35), (0, 0, 0),
         (0, 0, 1), {"effort": 150, "velocity": 630}, 0.01, 0.1),
        ("c_motor", "continuous", "bed", "c_motor", (-0.30, -0.15, -0.35), (0, 0, 0),
         (0, 0, 1), {"effort": 60, "velocity": 630}, 0.01, 0.05),
        ("z_carriage", "prismatic", "bed", "z_carriage", (0, 0, 0), (0, 0, 0), (0, 0, 1),
         {"lower": 0.0, "upper": 0.65, "effort": 8000, "velocity": 0.5}, 50.0, 20.0),
        ("x_slide", "prismatic", "z_carriage", "x_slide", (0, 0, 0), (0, 0, 0), (1, 0, 0),
         {"lower": 0.0, "upper": 0.30, "effort": 5000, "velocity": 0.5}, 50.0, 20.0),
        ("turret", "revolute", "x_slide", "turret", (0.18, 0, 0.06), (0, 0, 0), (0, 0, 1),
         {"lower": -6.2832, "upper": 6.2832, "effort": 300, "velocity": 6}, 0.01, 0.2),
        ("probe_mount", "fixed", "turret", "probe",
         (0.13 * math.cos(phi3), 0.13 * math.sin(phi3), 0.0), (0, 0, phi3), None, None,
         0.0, 0.0),
        ("probe_axial_mount", "fixed", "turret", "probe_axial",
         (0.13 * math.cos(phi_axial), 0.13 * math.sin(phi_axial), 0.0), (0, 0, phi_axial), None,
         None, 0.0, 0.0),
        ("s2_spindle", "continuous", "turret", "s2_spindle",
         (0.14 * math.cos(phi4), 0.14 * math.sin(phi4), 0.0),
         (-math.pi / 2, 0, phi4 - math.pi / 2),
         (0, 0, 1), {"effort": 20, "velocity": 630}, 0.01, 0.01),
        ("tailstock", "prismatic", "bed", "tailstock", (0, 0, 0.20), (0, 0, 0), (0, 0, 1),
         {"lower": 0.0, "upper": 0.70, "effort": 4000, "velocity": 0.2}, 50.0, 20.0),
    ]
    if variant != "c1":
        joints = [j for j in joints
                  if j[0] not in ("s1_motor", "c_motor", "probe_axial_mount")]
    return links, joints, meshes, stations


# ----------------------------------------------------------------------------------- emitters
VARIANT_FLAG = {"c1": "", "c2": " --variant c2"}

README_INTRO = {
    "c1": [],
    "c2": ["lathe-c1's bed, carriage, cross slide, turret and tailstock; the main spindle is",
           "driven directly by a frameless motor (C-axis manual 2: main spindle drive with rotary",
           "axis capability): the rotor sits on the spindle shaft inside the headstock, the",
           "stator in the headstock (its end cover `bed_stator_cover` shows at the back). No belt,",
           "no C-axis servo, no clutch: the one drive S1 is the spindle in speed control and the",
           "C axis in position control, with a drive parameter set for each.",
           ""],
}

SPINDLE_NOTES = {
    "c1": ["- `spindle`, `s1_motor`, `c_motor`: continuous about +z. The belt (S1) and the C-axis",
           "  dog clutch are couplings in `machine.yaml`, not URDF joints."],
    "c2": ["- `spindle`: continuous about +z, the frameless motor's rotor included in its",
           "  inertia (Izz 0.32 kg m^2: chuck 0.25, rotor 0.07); drive S1 acts on it directly."],
}

def urdf_text(links, joints, variant):
    L = ['<?xml version="1.0"?>',
         "<!-- lathe-%s: generated by tools/gen_lathe_model.py, do not edit; regenerate with"
         % variant,
         "     python3 tools/gen_lathe_model.py%s." % VARIANT_FLAG[variant],
         "     World = bed frame: x radial (machine X, toward the turret), y UP, z spindle axis",
         "     (machine Z, toward the tailstock); origin on the spindle axis in the headstock face",
         "     plane. Gravity is -y. Units: m, rad, kg. Meshes are in their link frames. -->",
         '<robot name="lathe_%s">' % variant]
    for name, rgba in MATERIALS:
        L.append('  <material name="%s"><color rgba="%s"/></material>'
                 % (name, " ".join("%.2f" % c for c in rgba)))
    for lk in links:
        mass, com, (ixx, iyy, izz) = lk["inertial"]
        L.append('  <link name="%s">' % lk["name"])
        L.append("    <inertial>")
        L.append('      <origin xyz="%s" rpy="0 0 0"/>' % fvec(com))
        L.append('      <mass value="%s"/>' % fnum(mass))
        L.append('      <inertia ixx="%s" ixy="0" ixz="0" iyy="%s" iyz="0" izz="%s"/>'
                 % (("%.6g" % ixx), ("%.6g" % iyy), ("%.6g" % izz)))
        L.append("    </inertial>")
        for pname, mesh, mat, _ in lk["parts"]:
            L.append('    <visual name="%s">' % pname)
            L.append('      <origin xyz="0 0 0" rpy="0 0 0"/>')
            L.append('      <geometry><mesh filename="meshes/%s.ply"/></geometry>' % mesh)
            L.append('      <material name="%s"/>' % mat)
            L.append("    </visual>")
        for pname, mesh, mat, collide in lk["parts"]:
            if not collide:
                continue
            L.append('    <collision name="%s">' % pname)
            L.append('      <origin xyz="0 0 0" rpy="0 0 0"/>')
            L.append('      <geometry><mesh filename="meshes/%s.ply"/></geometry>' % mesh)
            L.append("    </collision>")
        L.append("  </link>")
    for (name, jtype, parent, child, xyz, rpy, axis, limit, damping, friction) in joints:
        L.append('  <joint name="%s" type="%s">' % (name, jtype))
        L.append('    <parent link="%s"/>' % parent)
        L.append('    <child link="%s"/>' % child)
        L.append('    <origin xyz="%s" rpy="%s"/>' % (fvec(xyz), fvec(rpy)))
        if axis is not None:
            L.append('    <axis xyz="%s"/>' % fvec(axis))
        if limit is not None:
            attrs = " ".join('%s="%s"' % (k, fnum(limit[k]))
                             for k in ("lower", "upper", "effort", "velocity") if k in limit)
            L.append("    <limit %s/>" % attrs)
        L.append('    <dynamics damping="%s" friction="%s"/>' % (fnum(damping), fnum(friction)))
        L.append("  </joint>")
    L.append("</robot>")
    return "\n".join(L) + "\n"


def readme_text(links, joints, meshes, stations, variant):
    L = ["# lathe-%s machine model" % variant,
         ""] + README_INTRO[variant] + [
         "Generated by `tools/gen_lathe_model.py` (Python 3, standard library only; deterministic",
         "output). Do not edit `machine.urdf` or `meshes/` by hand: regenerate with",
         "",
         "    python3 tools/gen_lathe_model.py%s" % VARIANT_FLAG[variant],
         "",
         "`machine.yaml` (axes, drives, couplings, I/O) is written by hand and refers to the joint",
         "names below.",
         "",
         "## Frames and units",
         "- Metres, radians, kilograms. Meshes: ASCII PLY, triangles only, each corner with its",
         "  normal, each in its own link frame (all visual/collision origins are identity).",
         "- World frame = `bed` link frame: **x** radial (machine X, positive away from the",
         "  spindle axis toward the turret at the back), **y up** (gravity is -y, not the usual",
         "  URDF -z), **z** along the spindle axis (machine Z, positive toward the tailstock).",
         "  Origin on the spindle axis in the plane of the headstock face.",
         "- Every mesh is one closed, outward-wound solid; the ones used as `<collision>` are",
         "  convex (boxes, cylinders, prisms, the probe sphere). Visual-only details (bolts, rotation",
         "  markers, flutes, short fillers) have no `<collision>`.",
         "- The workpiece is not part of the model; the scene adds it (in the `spindle` frame).",
         "",
         "## Links",
         "| link | mass kg | inertia (ixx, iyy, izz) kg m^2 | meshes |",
         "|---|---|---|---|"]
    for lk in links:
        mass, com, ine = lk["inertial"]
        L.append("| `%s` | %s | %s | %s |" % (
            lk["name"], fnum(mass), ", ".join("%.4g" % v for v in ine),
            ", ".join(p[1] for p in lk["parts"])))
    L += ["",
          "## Joints",
          "| joint | type | parent -> child | origin xyz (rpy) | axis | limits |",
          "|---|---|---|---|---|---|"]
    for (name, jtype, parent, child, xyz, rpy, axis, limit, _, _) in joints:
        lim = "" if limit is None else ", ".join(
            "%s %s" % (k, fnum(limit[k])) for k in ("lower", "upper", "effort", "velocity")
            if k in limit)
        org = fvec(xyz) + ("" if rpy == (0, 0, 0) else " (%s)" % fvec(rpy))
        L.append("| `%s` | %s | %s -> %s | %s | %s | %s |" % (
            name, jtype, parent, child, org, "-" if axis is None else fvec(axis), lim))
    L += ["",
          "Joint notes:"] + SPINDLE_NOTES[variant] + [
          "- `turret` frame: origin on the turret axis, at the tool-tip plane; at zero joint",
          "  positions it lies at (0.18, 0, 0.06) in the world. Wide limits (+-2 pi): it indexes.",
          "- `s2_spindle` child +z points outward along station 4's ray; the end-mill tip is at",
          "  child z = 0.04.",
          "- `tailstock` frame origin = the live centre's point (cone tip).",
          "",
          "## Turret stations",
          "Station k sits at turret-frame angle phi_k = 180 deg - (k-1) * 30 deg (from +x toward",
          "+y). With turret joint angle q = (k-1) * 30 deg station k points along world -x, toward",
          "the spindle. All tool tips are at radius 0.18 m from the turret axis, at z = 0 of the",
          "turret frame; so the active tool's tip in the world is",
          "(x_slide, 0, z_carriage + 0.06): X = 0 is the spindle axis.",
          "",
          "| station | phi_k deg | tip in turret frame (m) | tool |",
          "|---|---|---|---|"]
    for k, phid, tip, tool in stations:
        L.append("| %d | %d | %s %s %s | %s |" % (k, phid, f6(tip[0]), f6(tip[1]), f6(tip[2]),
                                                 tool))
    L += ["",
          "Tool parts are visuals/collisions of the `turret` link named `turret_stKK_*`;",
          "station 1's insert cutting corner (80 deg rhombus in the ray-z plane, 5 mm thick",
          "tangentially) is exactly at the tip; station 2's gold tip is 3 mm wide in z; station 3",
          "is the `probe` link (ruby sphere r 3 mm, centre at radius 0.177); station 4 is the",
          "`s2_spindle` link; station 5 carries a radial drill with a 118 deg point."] + (
          ["Station %d is the `probe_axial` link: the same head on an arm to radius 0.18, the"
           % AXIAL_PROBE_STATION,
           "stylus bent along -z, ruby r 3 mm centred at radius 0.177 and %g mm ahead of the"
           % (AXIAL_PROBE_REACH * 1000),
           "tool-tip plane (toward the headstock): the floor and walls of a face groove."]
          if variant == "c1" else []) + [
          "",
          "## Meshes",
          "%d files in `meshes/`, %d triangles in total." % (
              len(meshes), sum(len(m.tris) for m in meshes.values())),
          ""]
    return "\n".join(L)


def write(path, text):
    with open(path, "w", newline="\n", encoding="ascii") as f:
        f.write(text)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--variant", choices=("c1", "c2"), default="c1")
    parser.add_argument("-q", dest="quiet", action="store_true", help="no mesh table")
    args = parser.parse_args()
    variant = args.variant
    model_dir = os.path.join(ROOT, "models", "lathe-" + variant)
    mesh_dir = os.path.join(model_dir, "meshes")
    links, joints, meshes, stations = build(variant)
    os.makedirs(mesh_dir, exist_ok=True)
    total_tris = total_bytes = 0
    rows = []
    for name in sorted(meshes):
        m = meshes[name]
        m.check_closed()
        text = m.ply_text("lathe-" + variant)
        write(os.path.join(mesh_dir, name + ".ply"), text)
        total_tris += len(m.tris)
        total_bytes += len(text)
        rows.append("%-32s %6d triangles %8d bytes" % (name + ".ply", len(m.tris), len(text)))
    write(os.path.join(model_dir, "machine.urdf"), urdf_text(links, joints, variant))
    write(os.path.join(model_dir, "README.md"),
          readme_text(links, joints, meshes, stations, variant))
    if not args.quiet:
        print("\n".join(rows))
        print("%d meshes, %d triangles, %d bytes of PLY" % (len(meshes), total_tris, total_bytes))


if __name__ == "__main__":
    main()
