// Loop limit positions by OpenSubdiv 3.5 (Far::TopologyRefiner, SCHEME_LOOP, PrimvarRefiner
// ::Limit): the independent reference for meshrefine's CPU Loop subdivision
// (scripts/check-loop-osd.sh). Reads from stdin a first line "STEPS BOUNDARY" (BOUNDARY:
// edge-only | edge-and-corner), then "v X Y Z" and "f A B C" lines (0-based); writes the limit
// positions of the vertices after STEPS uniform steps as "v X Y Z" lines.
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

using namespace OpenSubdiv;

struct Point {
    double p[3];
    void Clear(void * = nullptr) { p[0] = p[1] = p[2] = 0.0; }
    void AddWithWeight(Point const &s, double w) {
        p[0] += w * s.p[0];
        p[1] += w * s.p[1];
        p[2] += w * s.p[2];
    }
};

int main() {
    int steps = 0;
    std::string boundary;
    std::cin >> steps >> boundary;
    std::vector<Point> verts;
    std::vector<int> faces;
    std::string tag;
    while (std::cin >> tag) {
        if (tag == "v") {
            Point q;
            std::cin >> q.p[0] >> q.p[1] >> q.p[2];
            verts.push_back(q);
        } else if (tag == "f") {
            int a, b, c;
            std::cin >> a >> b >> c;
            faces.insert(faces.end(), {a, b, c});
        }
    }
    std::vector<int> counts(faces.size() / 3, 3);
    Far::TopologyDescriptor desc;
    desc.numVertices = (int)verts.size();
    desc.numFaces = (int)counts.size();
    desc.numVertsPerFace = counts.data();
    desc.vertIndicesPerFace = faces.data();
    Sdc::Options options;
    options.SetVtxBoundaryInterpolation(boundary == "edge-and-corner"
                                            ? Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                            : Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    Far::TopologyRefiner *refiner =
        Factory::Create(desc, Factory::Options(Sdc::SCHEME_LOOP, options));
    if (!refiner) {
        std::fprintf(stderr, "OpenSubdiv refused the mesh\n");
        return 1;
    }
    Far::TopologyRefiner::UniformOptions uniform(steps);
    uniform.fullTopologyInLastLevel = true; // Limit() needs the last level's full topology
    refiner->RefineUniform(uniform);
    // Weights in double, like meshrefine's reference.
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    std::vector<Point> level = verts;
    for (int l = 1; l <= steps; ++l) {
        std::vector<Point> next(refiner->GetLevel(l).GetNumVertices());
        Point *src = level.data(), *dst = next.data();
        primvar.Interpolate(l, src, dst);
        level = next;
    }
    std::vector<Point> limit(level.size());
    Point *src = level.data(), *dst = limit.data();
    primvar.Limit(src, dst);
    for (auto const &q : limit) {
        std::printf("v %.17g %.17g %.17g\n", q.p[0], q.p[1], q.p[2]);
    }
    delete refiner;
    return 0;
}
