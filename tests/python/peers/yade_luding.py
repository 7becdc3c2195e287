# Two equal spheres under Yade's Law2_ScGeom_LudingPhys_Basic, the second moved at constant speed along a
# path of turning overlaps (into contact, back onto the adhesion limit, reloaded, on past alpha*, out),
# the normal force written every step: tests/python/test_peers.py compares it with `powderfmu curve`
# (luding_variant = mercurydpm). Run as `yade -n -x yade_luding.py ARGS.json OUT.txt`; ARGS.json holds
# radius, density, k1, kp, kc, phi_f, dt, v and turns (overlaps in m, the last one negative: apart).
import json
import sys

args = json.load(open(sys.argv[-2]))
out = open(sys.argv[-1], "w")
r = args["radius"]
mat = O.materials.append(LudingMat(k1=args["k1"], kp=args["kp"], kc=args["kc"], PhiF=args["phi_f"], G0=0.0, ks=0.0,
                                   frictionAngle=0.0, density=args["density"]))
O.bodies.append(sphere((0, 0, 0), r, material=mat, fixed=True))
mover = O.bodies.append(sphere((2 * r - args["turns"][-1], 0, 0), r, material=mat))
O.bodies[mover].state.blockedDOFs = "xyzXYZ"
turns = list(args["turns"])
state = {"leg": 0}


def overlap():
    return 2 * r - O.bodies[mover].state.pos[0]


def set_direction():
    # Moving toward the next turning overlap: -x increases the overlap.
    target = turns[state["leg"]]
    O.bodies[mover].state.vel = Vector3(-args["v"] if target > overlap() else args["v"], 0, 0)


def record():
    f, a = 0.0, overlap()
    if O.interactions.has(0, mover) and O.interactions[0, mover].isReal:
        i = O.interactions[0, mover]
        # The normal force along the contact normal (positive in compression), at the overlap it was
        # computed from (the body has moved on since).
        f, a = i.phys.normalForce.dot(i.geom.normal), i.geom.penetrationDepth
    out.write("%.17g %.17g %d\n" % (a, f, state["leg"]))
    a, target = overlap(), turns[state["leg"]]
    if (O.bodies[mover].state.vel[0] < 0 and a >= target) or (O.bodies[mover].state.vel[0] > 0 and a <= target):
        state["leg"] += 1
        if state["leg"] == len(turns):
            out.close()
            O.pause()
            return
        set_direction()


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_LudingMat_LudingMat_LudingPhys()], [Law2_ScGeom_LudingPhys_Basic()]),
    NewtonIntegrator(damping=0.0),
    PyRunner(iterPeriod=1, command="record()"),
]
O.dt = args["dt"]
set_direction()
O.run(10 ** 8, True)
