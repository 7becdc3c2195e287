# Two equal spheres under Yade's Law2_ScGeom_LudingPhys_Basic colliding head-on at a relative speed v (each
# at v/2), free, no damping: prints the relative rebound speed / v (the restitution) and the largest overlap.
# Run as `yade -n -x yade_luding_impact.py ARGS.json OUT.json`; ARGS.json holds radius, density, k1, kp,
# kc, phi_f, dt, v. tests/python/test_peers.py compares with each reading's energy balance.
import json
import sys

args = json.load(open(sys.argv[-2]))
r, v = args["radius"], args["v"]
mat = O.materials.append(LudingMat(k1=args["k1"], kp=args["kp"], kc=args["kc"], PhiF=args["phi_f"], G0=0.0, ks=0.0,
                                   frictionAngle=0.0, density=args["density"]))
a = O.bodies.append(sphere((0, 0, 0), r, material=mat))
b = O.bodies.append(sphere((2 * r + 1e-10, 0, 0), r, material=mat))
O.bodies[a].state.vel = Vector3(v / 2, 0, 0)
# Only the motion along the line of centres: the test is of the normal law.
O.bodies[a].state.blockedDOFs = "yzXYZ"
O.bodies[b].state.blockedDOFs = "yzXYZ"
O.bodies[b].state.vel = Vector3(-v / 2, 0, 0)
result = {"max_overlap": 0.0, "touched": False}


def watch():
    gap = O.bodies[b].state.pos[0] - O.bodies[a].state.pos[0] - 2 * r
    result["max_overlap"] = max(result["max_overlap"], -gap)
    touching = O.interactions.has(a, b) and O.interactions[a, b].isReal
    result["touched"] = result["touched"] or touching
    if result["touched"] and gap > 1e-9 and not touching:
        rel = O.bodies[b].state.vel[0] - O.bodies[a].state.vel[0]
        result["restitution"] = rel / v
        json.dump(result, open(sys.argv[-1], "w"))
        O.pause()


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_LudingMat_LudingMat_LudingPhys()], [Law2_ScGeom_LudingPhys_Basic()]),
    NewtonIntegrator(damping=0.0),
    PyRunner(iterPeriod=1, command="watch()"),
]
O.dt = args["dt"]
O.run(10 ** 7, True)
if "restitution" not in result:
    result["restitution"] = 0.0  # stuck: still in contact after the run
    json.dump(result, open(sys.argv[-1], "w"))
