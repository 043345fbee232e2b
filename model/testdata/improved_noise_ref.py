#!/usr/bin/python3
"""Expected values for perlin2002 (model/improved_noise.cpp): an independent transliteration.

Ken Perlin's "JAVA REFERENCE IMPLEMENTATION OF IMPROVED NOISE - COPYRIGHT 2002 KEN PERLIN."
(ImprovedNoise.java, https://mrl.nyu.edu/~perlin/noise/), read from the copies in the
GitHub repositories Harshit00yadav/PerlinNoise (ImprovedNoise.java, commit 92ca0c1f) and
Syritx/improved-noise (ImprovedNoise.java, commit dcefdc28), which agree on noise(), fade(),
lerp(), grad() and the permutation. Transliterated line by line: Python floats are IEEE
doubles and every operation below is the Java one in the same order, so the values are the
Java program's to the last bit (checked once against javac/java: see --java).

    improved_noise_ref.py > model/testdata/improved_noise_ref.txt      # regenerate the table
    improved_noise_ref.py --check model/testdata/improved_noise_ref.txt  # ctest: table == this
    improved_noise_ref.py --java DIR   # also write DIR/ImprovedNoiseTable.java (the published
                                       # class plus a main() printing the same table) to diff

Table: one point per line, "x y z noise" as C99 hex floats (exact).
"""
import math
import random
import sys

PERMUTATION = [151, 160, 137, 91, 90, 15,
    131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69, 142, 8, 99, 37, 240, 21, 10, 23,
    190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32, 57, 177, 33,
    88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175, 74, 165, 71, 134, 139, 48, 27, 166,
    77, 146, 158, 231, 83, 111, 229, 122, 60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244,
    102, 143, 54, 65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169, 200, 196,
    135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186, 3, 64, 52, 217, 226, 250, 124, 123,
    5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42,
    223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9,
    129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104, 218, 246, 97, 228,
    251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241, 81, 51, 145, 235, 249, 14, 239, 107,
    49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254,
    138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180]
p = PERMUTATION + PERMUTATION  # static { for (i..256) p[256+i] = p[i] = permutation[i]; }


def fade(t):
    return t * t * t * (t * (t * 6 - 15) + 10)


def lerp(t, a, b):
    return a + t * (b - a)


def grad(hash_, x, y, z):
    h = hash_ & 15                        # CONVERT LO 4 BITS OF HASH CODE
    u = x if h < 8 else y                 # INTO 12 GRADIENT DIRECTIONS.
    v = y if h < 4 else (x if h == 12 or h == 14 else z)
    return (u if (h & 1) == 0 else -u) + (v if (h & 2) == 0 else -v)


def java_int(d):
    """Java's (int) of a double: truncation toward zero, saturating (points here are small)."""
    assert abs(d) < 2 ** 31
    return int(d)


def noise(x, y, z):
    X = java_int(math.floor(x)) & 255     # FIND UNIT CUBE THAT
    Y = java_int(math.floor(y)) & 255     # CONTAINS POINT.
    Z = java_int(math.floor(z)) & 255
    x -= math.floor(x)                    # FIND RELATIVE X,Y,Z
    y -= math.floor(y)                    # OF POINT IN CUBE.
    z -= math.floor(z)
    u = fade(x)                           # COMPUTE FADE CURVES
    v = fade(y)                           # FOR EACH OF X,Y,Z.
    w = fade(z)
    A = p[X] + Y; AA = p[A] + Z; AB = p[A + 1] + Z       # HASH COORDINATES OF
    B = p[X + 1] + Y; BA = p[B] + Z; BB = p[B + 1] + Z   # THE 8 CUBE CORNERS,
    return lerp(w, lerp(v, lerp(u, grad(p[AA], x, y, z),            # AND ADD
                                   grad(p[BA], x - 1, y, z)),        # BLENDED
                           lerp(u, grad(p[AB], x, y - 1, z),         # RESULTS
                                   grad(p[BB], x - 1, y - 1, z))),   # FROM  8
                   lerp(v, lerp(u, grad(p[AA + 1], x, y, z - 1),     # CORNERS
                                   grad(p[BA + 1], x - 1, y, z - 1)),  # OF CUBE
                           lerp(u, grad(p[AB + 1], x, y - 1, z - 1),
                                   grad(p[BB + 1], x - 1, y - 1, z - 1))))


def points():
    """2000 random points in [-300, 300)^3 (past the 256 period, negative coordinates), 200
    near lattice planes and 24 exactly on lattice points/planes."""
    rng = random.Random(2002)
    pts = [(rng.uniform(-300, 300), rng.uniform(-300, 300), rng.uniform(-300, 300)) for _ in range(2000)]
    for _ in range(200):
        c = [rng.randint(-260, 260) + rng.choice((0.0, 1e-9, -1e-9, 1e-3, -1e-3)) for _ in range(3)]
        pts.append(tuple(c))
    for i in range(24):
        pts.append((float(i - 12), float(3 * i % 7), 0.5 * i))
    return pts


def table():
    return "".join(f"{x.hex()} {y.hex()} {z.hex()} {noise(x, y, z).hex()}\n" for x, y, z in points())


JAVA_MAIN = """
   public static void main(String[] args) {
      java.io.BufferedReader in = new java.io.BufferedReader(new java.io.InputStreamReader(System.in));
      try {
         for (String line; (line = in.readLine()) != null; ) {
            String[] f = line.trim().split(" ");
            double x = Double.parseDouble(f[0]), y = Double.parseDouble(f[1]), z = Double.parseDouble(f[2]);
            System.out.println(Double.toHexString(noise(x, y, z)));
         }
      } catch (java.io.IOException e) { throw new RuntimeException(e); }
   }
"""


def main(argv):
    if len(argv) >= 2 and argv[0] == "--check":
        with open(argv[1]) as f:
            have = f.read()
        if have != table():
            print(f"{argv[1]} differs from the transliteration's values", file=sys.stderr)
            return 1
        print(f"{argv[1]}: {len(have.splitlines())} points equal the transliteration's values")
        return 0
    if len(argv) >= 2 and argv[0] == "--java":
        # Perlin's class as published (noise, fade, lerp, grad, permutation) plus a main()
        # reading "x y z" lines and printing noise in Java hex, compiled and run by a real JVM.
        import pathlib, subprocess
        d = pathlib.Path(argv[1])
        d.mkdir(parents=True, exist_ok=True)
        (d / "ImprovedNoiseTable.java").write_text("public final class ImprovedNoiseTable {\n" + JAVA_BODY
                                                   + JAVA_MAIN + "}\n")
        pts = points()
        subprocess.run(["javac", "ImprovedNoiseTable.java"], cwd=d, check=True)
        out = subprocess.run(["java", "-cp", str(d), "ImprovedNoiseTable"], check=True, capture_output=True,
                             text=True, input="".join(f"{x.hex()} {y.hex()} {z.hex()}\n" for x, y, z in pts))
        java = [float.fromhex(v) for v in out.stdout.split()]
        bad = [(pt, j) for pt, j in zip(pts, java) if j != noise(*pt)]
        if len(java) != len(pts) or bad:
            print(f"java differs at {len(bad)} of {len(pts)} points: {bad[:3]}", file=sys.stderr)
            return 1
        print(f"java: {len(pts)} points equal the transliteration's values bit for bit")
        return 0
    sys.stdout.write(table())
    return 0


# Perlin's published class body, for --java (the cross-check against a real JVM).
JAVA_BODY = """
   static public double noise(double x, double y, double z) {
      int X = (int)Math.floor(x) & 255,                  // FIND UNIT CUBE THAT
          Y = (int)Math.floor(y) & 255,                  // CONTAINS POINT.
          Z = (int)Math.floor(z) & 255;
      x -= Math.floor(x);                                // FIND RELATIVE X,Y,Z
      y -= Math.floor(y);                                // OF POINT IN CUBE.
      z -= Math.floor(z);
      double u = fade(x),                                // COMPUTE FADE CURVES
             v = fade(y),                                // FOR EACH OF X,Y,Z.
             w = fade(z);
      int A = p[X  ]+Y, AA = p[A]+Z, AB = p[A+1]+Z,      // HASH COORDINATES OF
          B = p[X+1]+Y, BA = p[B]+Z, BB = p[B+1]+Z;      // THE 8 CUBE CORNERS,

      return lerp(w, lerp(v, lerp(u, grad(p[AA  ], x  , y  , z   ),  // AND ADD
                                     grad(p[BA  ], x-1, y  , z   )), // BLENDED
                             lerp(u, grad(p[AB  ], x  , y-1, z   ),  // RESULTS
                                     grad(p[BB  ], x-1, y-1, z   ))),// FROM  8
                     lerp(v, lerp(u, grad(p[AA+1], x  , y  , z-1 ),  // CORNERS
                                     grad(p[BA+1], x-1, y  , z-1 )), // OF CUBE
                             lerp(u, grad(p[AB+1], x  , y-1, z-1 ),
                                     grad(p[BB+1], x-1, y-1, z-1 ))));
   }
   static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
   static double lerp(double t, double a, double b) { return a + t * (b - a); }
   static double grad(int hash, double x, double y, double z) {
      int h = hash & 15;                      // CONVERT LO 4 BITS OF HASH CODE
      double u = h<8 ? x : y,                 // INTO 12 GRADIENT DIRECTIONS.
             v = h<4 ? y : h==12||h==14 ? x : z;
      return ((h&1) == 0 ? u : -u) + ((h&2) == 0 ? v : -v);
   }
   static final int p[] = new int[512], permutation[] = { """ + ",".join(map(str, PERMUTATION)) + """
   };
   static { for (int i=0; i < 256 ; i++) p[256+i] = p[i] = permutation[i]; }
"""

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
