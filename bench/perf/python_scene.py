"""A kept scene against a load per render: N renders of one asset through kiln.Scene.render and N
through kiln.render, alternated in rounds, at a small size (64x48, 1 spp by default) so that loading
is what differs. Prints the seconds of each round and the medians per render, per asset.

    PYTHONPATH=build/python python3 bench/perf/python_scene.py [ASSET ...] [--renders 100]
        [--rounds 3] [--width 64 --height 48 --spp 1 --threads 2]

Each render of the kept scene turns the camera a little (look_from moves), so that it poses and
updates the backend as a camera move does; kiln.render gets the same options."""
import argparse
import math
import os
import statistics
import time

import kiln

SOURCE = os.path.join(os.path.dirname(__file__), "..", "..")
DEFAULT_ASSETS = [os.path.join(SOURCE, "scenes", "cornell_box.gltf"),
                  os.path.join(SOURCE, "..", "shared", "assets", "ToyCar", "glTF", "ToyCar.gltf")]


def views(asset, count, options):
    """count look_from/look_at pairs orbiting the asset's bounds, as kiln info gives them."""
    bounds = kiln.info(asset, **options)["bounds"]
    low, high = bounds["min"], bounds["max"]
    centre = [(a + b) / 2 for a, b in zip(low, high)]
    radius = 1.8 * math.dist(low, high)
    return [{"look_from": (centre[0] + radius * math.sin(i / count), centre[1] + radius * 0.3,
                           centre[2] + radius * math.cos(i / count)), "look_at": tuple(centre)}
            for i in range(count)]


def timed(renders):
    start = time.perf_counter()
    for render in renders:
        render()
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("assets", nargs="*", default=DEFAULT_ASSETS)
    parser.add_argument("--renders", type=int, default=100)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--width", type=int, default=64)
    parser.add_argument("--height", type=int, default=48)
    parser.add_argument("--spp", type=int, default=1)
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()
    options = {"width": args.width, "height": args.height, "spp": args.spp, "threads": args.threads}
    print(f"{args.renders} renders a round at {args.width}x{args.height}, {args.spp} spp, {args.threads} threads")
    for asset in args.assets:
        if not os.path.exists(asset):
            print(f"{asset}: absent, skipped")
            continue
        looks = views(asset, args.renders, options)
        kept, fresh = [], []
        for _ in range(args.rounds):
            start = time.perf_counter()
            scene = kiln.load(asset, **options)
            kept.append(time.perf_counter() - start +
                        timed([lambda look=look: scene.render(**look) for look in looks]))
            fresh.append(timed([lambda look=look: kiln.render(asset, **options, **look) for look in looks]))
        name = os.path.basename(asset)
        print(f"{name}: kiln.load + Scene.render: " + ", ".join(f"{s:.2f}" for s in kept) + " s; "
              f"kiln.render: " + ", ".join(f"{s:.2f}" for s in fresh) + " s")
        k, f = statistics.median(kept), statistics.median(fresh)
        print(f"{name}: median {k:.2f} s against {f:.2f} s ({1000 * k / args.renders:.1f} ms against "
              f"{1000 * f / args.renders:.1f} ms a render, {f / k:.1f}x)")


if __name__ == "__main__":
    main()
