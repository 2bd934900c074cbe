// tools/make_mesh.cpp -- writes Wavefront OBJ meshes to standard output, to try rt's `mesh`
// statement on models of any size (`make build/make_mesh`).
//
//   make_mesh sphere LEVEL   an icosphere: an icosahedron whose triangles are split in four LEVEL
//                            times, every vertex pushed out onto the unit sphere: 20 * 4^LEVEL
//                            triangles (LEVEL 0..9)
//   make_mesh terrain N      a height field over the square [-1, 1] x [-1, 1] of y = 0: an N x N
//                            grid of squares, two triangles each, 2 N^2 triangles (N 1..4000)
//   ... normals              the same, with the true surface's normal at each vertex (`vn`, named
//                            by every face's corners as v//vn): the sphere's is its position, the
//                            terrain's comes from the slopes of its height function
//
// Vertices are shared (each written once), and every face is wound counter-clockwise seen from
// outside, so (b - a) x (c - a) points out of the sphere and up from the terrain.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

struct Point {
    double x, y, z;
};

struct Face {
    int a, b, c; // indices into the vertices, from 0
};

static Point OnUnitSphere(Point p) {
    double length = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    return {p.x / length, p.y / length, p.z / length};
}

// The vertex halfway along edge (i, j), pushed onto the sphere; made once per edge, so the two
// triangles that share the edge share this vertex too (the mesh stays closed).
static int Midpoint(int i, int j, std::vector<Point> *vertices,
                    std::map<std::pair<int, int>, int> *made) {
    std::pair<int, int> edge(std::min(i, j), std::max(i, j));
    auto found = made->find(edge);
    if (found != made->end())
        return found->second;
    Point a = (*vertices)[i], b = (*vertices)[j];
    vertices->push_back(OnUnitSphere({(a.x + b.x) / 2, (a.y + b.y) / 2, (a.z + b.z) / 2}));
    (*made)[edge] = (int)vertices->size() - 1;
    return (int)vertices->size() - 1;
}

// The icosahedron: its 12 corners are the cyclic permutations of (+-1, +-phi, 0), phi the golden
// ratio; 20 faces, counter-clockwise seen from outside.
static void Icosahedron(std::vector<Point> *vertices, std::vector<Face> *faces) {
    double t = (1 + std::sqrt(5.0)) / 2;
    Point corners[12] = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (Point p : corners)
        vertices->push_back(OnUnitSphere(p));
    *faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
              {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
              {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
}

// Splits every face in four at its edges' midpoints, keeping the winding: the three corner
// triangles and the middle one.
static void Subdivide(std::vector<Point> *vertices, std::vector<Face> *faces) {
    std::map<std::pair<int, int>, int> made;
    std::vector<Face> split;
    for (Face f : *faces) {
        int ab = Midpoint(f.a, f.b, vertices, &made), bc = Midpoint(f.b, f.c, vertices, &made),
            ca = Midpoint(f.c, f.a, vertices, &made);
        split.push_back({f.a, ab, ca});
        split.push_back({f.b, bc, ab});
        split.push_back({f.c, ca, bc});
        split.push_back({ab, bc, ca});
    }
    faces->swap(split);
}

// A gentle landscape: a few sine waves, heights within +-0.25.
static double Height(double x, double z) {
    return 0.15 * std::sin(3 * x) * std::cos(2 * z) + 0.05 * std::sin(5 * x + 7 * z) +
           0.05 * std::cos(11 * x - 3 * z);
}

// Vertex (i, j) of the grid is at index j (N + 1) + i; square (i, j) becomes the triangles
// (i,j) (i,j+1) (i+1,j+1) and (i,j) (i+1,j+1) (i+1,j), whose (b - a) x (c - a) point up (+y).
static void Terrain(int n, std::vector<Point> *vertices, std::vector<Face> *faces) {
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double x = -1 + 2.0 * i / n, z = -1 + 2.0 * j / n;
            vertices->push_back({x, Height(x, z), z});
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int v00 = j * (n + 1) + i, v10 = v00 + 1, v01 = v00 + n + 1, v11 = v01 + 1;
            faces->push_back({v00, v01, v11});
            faces->push_back({v00, v11, v10});
        }
}

// The terrain's unit normal at (x, z): (-dh/dx, 1, -dh/dz), normalised.
static Point TerrainNormal(Point p) {
    double dx = 0.45 * std::cos(3 * p.x) * std::cos(2 * p.z) + 0.25 * std::cos(5 * p.x + 7 * p.z) -
                0.55 * std::sin(11 * p.x - 3 * p.z);
    double dz = -0.3 * std::sin(3 * p.x) * std::sin(2 * p.z) + 0.35 * std::cos(5 * p.x + 7 * p.z) +
                0.15 * std::sin(11 * p.x - 3 * p.z);
    return OnUnitSphere({-dx, 1, -dz});
}

// OBJ counts vertices from 1. %.9g: nine significant digits, enough for a float to read back
// exactly, and a third shorter than the 17 a double would need. With normals (one a vertex, the
// same number), each corner is written v//vn.
static void WriteObj(const char *what, const std::vector<Point> &vertices,
                     const std::vector<Face> &faces, Point (*normal)(Point)) {
    printf("# %s: %zu vertices, %zu triangles%s (rt's tools/make_mesh)\n", what, vertices.size(),
           faces.size(), normal ? ", a normal at each vertex" : "");
    for (Point p : vertices)
        printf("v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    if (normal)
        for (Point p : vertices) {
            Point n = normal(p);
            printf("vn %.9g %.9g %.9g\n", n.x, n.y, n.z);
        }
    for (Face f : faces)
        if (normal)
            printf("f %d//%d %d//%d %d//%d\n", f.a + 1, f.a + 1, f.b + 1, f.b + 1, f.c + 1,
                   f.c + 1);
        else
            printf("f %d %d %d\n", f.a + 1, f.b + 1, f.c + 1);
}

// A whole number in [lo, hi], or -1.
static int Count(const char *text, int lo, int hi) {
    char *end;
    long value = strtol(text, &end, 10);
    return *text && !*end && value >= lo && value <= hi ? (int)value : -1;
}

static Point SphereNormal(Point p) { return OnUnitSphere(p); }

int main(int argc, char **argv) {
    std::vector<Point> vertices;
    std::vector<Face> faces;
    bool normals = argc == 4 && !strcmp(argv[3], "normals");
    bool shape = argc == 3 || normals;
    int n = shape ? Count(argv[2], 0, 9) : -1;
    if (shape && !strcmp(argv[1], "sphere") && n >= 0) {
        Icosahedron(&vertices, &faces);
        for (int level = 0; level < n; level++)
            Subdivide(&vertices, &faces);
        WriteObj("icosphere", vertices, faces, normals ? SphereNormal : nullptr);
        return 0;
    }
    n = shape ? Count(argv[2], 1, 4000) : -1;
    if (shape && !strcmp(argv[1], "terrain") && n >= 1) {
        Terrain(n, &vertices, &faces);
        WriteObj("terrain", vertices, faces, normals ? TerrainNormal : nullptr);
        return 0;
    }
    fprintf(stderr, "usage: make_mesh sphere LEVEL (0..9) [normals] | make_mesh terrain N "
                    "(1..4000) [normals]\n");
    return 2;
}
