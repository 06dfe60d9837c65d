"""A step of scripts/bench_target_mhz.sh (its arguments as there: sys.argv[1:])."""
import random, sys
n, seed, models = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3].split()
rng = random.Random(seed)
for i in range(n):
    family = rng.choice(["ice40", "ecp5"])
    f = rng.choice([25, 30, 40, 50, 60, 75, 90] if family == "ice40" else [40, 50, 75, 100, 125, 150])
    widths = [rng.randint(8, 15), rng.randint(6, 10), rng.randint(4, 8), rng.randint(8, 15)]
    print(rng.choice(models), family, f, *widths)
