// Private to verifier/: the worklist sweep shared by the damper and spring forward projections (Buckley
// Alg 4.1 steps 1-3): process every atom with pending seeds, faces then edges then vertices, until nothing is
// pending or the step cap is reached. Returns true when work was still pending at the cap (callers fall back
// soundly).
#pragma once

namespace cmt::face_geometry {

template <class FacePending, class ProcessFace, class EdgePending, class ProcessEdge, class VertexPending,
          class ProcessVertex>
bool sweep_until_stable(int faces, int edges, int vertices, const int& steps, int max_steps,
                        FacePending face_pending, ProcessFace process_face, EdgePending edge_pending,
                        ProcessEdge process_edge, VertexPending vertex_pending,
                        ProcessVertex process_vertex) {
  bool progress = true;
  while (progress && steps <= max_steps) {
    progress = false;
    for (int i = 0; i < faces; ++i)
      if (face_pending(i)) {
        progress = true;
        process_face(i);
      }
    for (int i = 0; i < edges; ++i)
      if (edge_pending(i)) {
        progress = true;
        process_edge(i);
      }
    for (int i = 0; i < vertices; ++i)
      if (vertex_pending(i)) {
        progress = true;
        process_vertex(i);
      }
  }
  return progress;
}

}  // namespace cmt::face_geometry
