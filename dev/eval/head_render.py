"""A textured 3D head made from one real frame, re-rendered turned in yaw and
pitch: truth beyond the image plane (turn_truth.py).

The head is the face mesh's 468 points with their depth (MediaPipe's
face_landmark network, as the estimator's mesh_pnp model runs it), and a shell
of three rings around them out to the head's outline, so that hair, ears, jaw
and neck turn with the face. The shell's outer ring lies at the pivot's depth:
turning about the pivot moves it little, so the head stays joined to the
static background (the rest of the real frame) as a rubber sheet.

The camera is the estimator's: x right, y down, z forward, focal length the
frame's long side, the principal point in the middle. World units are pixels
at the face's distance: a landmark at image point (u, v) with mesh depth z
sits at depth Z = f + z, at ((u - cx) Z / f, (v - cy) Z / f), so that the unturned
head projects onto the real frame exactly.

A turn R (camera coordinates) moves every vertex about the pivot: p' = c + R (p - c),
the pivot c behind the face by PIVOT_BEHIND face widths (the neck's joint,
about 10 cm behind the nose of a 14 cm wide face). Each frame is drawn by the
painter's rule: the shell first, as it lies beside and behind the face at any
turn up to 40 deg, then the face's triangles far to near; each triangle's
texture is the real frame's pixels under its unturned place. Where a turn
folds the face's far side, its outline frays (docs/evaluation.md: the range
the renders are trusted in); turn_truth.py adds the sensor noise and the
JPEG of truth_clips.py.

Nothing made here is committed: heads are built at run time from
../shared/data/videos and the models fetched by dev/models/fetch_models.sh.
"""
import numpy as np

PIVOT_BEHIND = 0.7                # face widths from the nose tip back to the pivot
PIVOT_BELOW = 0.15                # face widths from the face's centre down to the pivot
SHELL_SCALES = (1.08, 1.2, 1.45)  # the shell's rings: the face outline scaled about its centre
SHELL_DEPTHS = (0.6, 1.0, 1.0)    # and their depths, from the outline's (0) to the pivot's (1)
SHELL_POINTS = 36                 # points per ring


def landmarks(image, box, model_path):
    """The face mesh's 468 points (x, y in frame px, z in px, smaller nearer) of the face in `box`
    (x_min, y_min, x_max, y_max): the network run twice, the second time on the region its own
    points give (the estimator's region: the box's long side x 1.5)."""
    import cv2
    import onnxruntime
    session = onnxruntime.InferenceSession(model_path, providers=["CPUExecutionProvider"])
    centre = np.array([(box[0] + box[2]) / 2.0, (box[1] + box[3]) / 2.0])
    side = 1.5 * max(box[2] - box[0], box[3] - box[1])
    for _ in range(2):
        scale = 192.0 / side
        to_input = np.array([[scale, 0, 96.0 - scale * centre[0]], [0, scale, 96.0 - scale * centre[1]]])
        patch = cv2.warpAffine(image, to_input, (192, 192), flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT)
        rgb = cv2.cvtColor(patch, cv2.COLOR_BGR2RGB).astype(np.float32) / 255.0
        out = session.run(None, {session.get_inputs()[0].name: rgb.transpose(2, 0, 1)[None]})
        xyz = np.asarray(out[0], dtype=float).reshape(-1, 3)[:468]
        points = np.column_stack([(xyz[:, 0] - 96.0) / scale + centre[0], (xyz[:, 1] - 96.0) / scale + centre[1],
                                  xyz[:, 2] / scale])
        low, high = points[:, :2].min(axis=0), points[:, :2].max(axis=0)
        centre, side = (low + high) / 2.0, 1.5 * float(np.max(high - low))
    return points


class Head:
    """A textured head: vertices (n, 3) in camera coordinates, their texture coordinates (n, 2) in
    the real frame, triangles (m, 3), the pivot, the frame it came from and its camera."""

    def __init__(self, image, points):
        from scipy.spatial import ConvexHull
        h, w = image.shape[:2]
        self.image, self.focal = image, float(max(w, h))
        self.principal = np.array([w / 2.0, h / 2.0])
        face = self._unproject(points[:, :2], self.focal + points[:, 2])
        hull_index = ConvexHull(points[:, :2]).vertices
        hull = points[hull_index]
        centre = hull[:, :2].mean(axis=0)
        self.face_width = float(np.ptp(points[:, 0]))
        nose_z = float(face[:, 2].min())
        pivot_z = nose_z + PIVOT_BEHIND * self.face_width
        self.pivot = self._unproject(centre + [0.0, PIVOT_BELOW * self.face_width], pivot_z)
        outline, outline_z = self._outline(hull, centre)
        edge_z = self.focal + outline_z  # the face outline's depth, point by point
        rings, places, texture = [face], [points[:, :2]], [points[:, :2]]
        for scale, depth in zip(SHELL_SCALES, SHELL_DEPTHS):  # the head's side curving back to the pivot
            uv = centre + scale * (outline - centre)
            rings.append(self._unproject(uv, edge_z + depth * (pivot_z - edge_z)))
            places.append(uv)
            texture.append(uv)
        self.vertices, self.texture = np.vstack(rings), np.vstack(texture)
        self.triangles = self._triangles(np.vstack(places), len(points), hull_index)
        self.of_face = (self.triangles < len(points)).all(axis=1)

    @staticmethod
    def _triangles(places, face_count, hull_index):
        """The face's own triangles (its points alone), then the shell's: between the face's outline
        (its convex hull) and the rings, none inside the outline (places: the vertices in the frame)."""
        from scipy.spatial import Delaunay
        face = Delaunay(places[:face_count]).simplices
        shell_points = np.concatenate([hull_index, np.arange(face_count, len(places))])
        shell = shell_points[Delaunay(places[shell_points]).simplices]
        return np.vstack([face, shell[(shell >= face_count).any(axis=1)]])

    def _unproject(self, uv, depth):
        """Camera coordinates of image points uv (n, 2) at depth (n or scalar)."""
        depth = np.broadcast_to(np.asarray(depth, dtype=float), (np.atleast_2d(uv).shape[0],))
        xy = (np.atleast_2d(uv) - self.principal) * depth[:, None] / self.focal
        out = np.column_stack([xy, depth])
        return out if np.ndim(uv) == 2 else out[0]

    @staticmethod
    def _outline(hull, centre):
        """SHELL_POINTS points on the face's outline (hull: its points, x y z), evenly spaced in
        angle about its centre, and their mesh depth."""
        angles = np.arctan2(hull[:, 1] - centre[1], hull[:, 0] - centre[0])
        radii = np.hypot(hull[:, 0] - centre[0], hull[:, 1] - centre[1])
        order = np.argsort(angles)
        a = np.concatenate([angles[order] - 2 * np.pi, angles[order], angles[order] + 2 * np.pi])
        wanted = np.linspace(-np.pi, np.pi, SHELL_POINTS, endpoint=False)
        radius = np.interp(wanted, a, np.tile(radii[order], 3))
        z = np.interp(wanted, a, np.tile(hull[order, 2], 3))
        return centre + np.column_stack([radius * np.cos(wanted), radius * np.sin(wanted)]), z

    def project(self, turn):
        """The vertices turned by `turn` (3x3, camera coordinates) about the pivot, in image px, and their depth."""
        p = self.pivot + (self.vertices - self.pivot) @ np.asarray(turn).T
        return self.principal + self.focal * p[:, :2] / p[:, 2:3], p[:, 2]

    def render(self, turn):
        """The frame with the head turned by `turn`: the real frame behind, the head drawn far to near."""
        import cv2
        uv, depth = self.project(turn)
        h, w = self.image.shape[:2]
        ids = np.full((h, w), -1, dtype=np.int32)
        order = np.lexsort((-depth[self.triangles].mean(axis=1), self.of_face))  # the shell, then the face far to near
        for t in order:
            cv2.fillConvexPoly(ids, np.rint(uv[self.triangles[t]] * 16).astype(np.int32), int(t), cv2.LINE_8, 4)
        ys, xs = np.nonzero(ids >= 0)
        maps = self._texture_maps(uv, ids[ys, xs], xs, ys)
        map_x = np.tile(np.arange(w, dtype=np.float32), (h, 1))
        map_y = np.tile(np.arange(h, dtype=np.float32)[:, None], (1, w))
        map_x[ys, xs], map_y[ys, xs] = maps[:, 0], maps[:, 1]
        return cv2.remap(self.image, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REFLECT_101)

    def _texture_maps(self, uv, triangle, xs, ys):
        """Where each drawn pixel (xs, ys) of `triangle` takes its colour in the real frame: its
        barycentric coordinates in the turned triangle, applied to the unturned one."""
        corners = uv[self.triangles[triangle]]            # (k, 3, 2)
        source = self.texture[self.triangles[triangle]]   # (k, 3, 2)
        e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
        d = np.column_stack([xs, ys]) - corners[:, 0]
        det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
        det = np.where(np.abs(det) < 1e-9, 1e-9, det)
        b1 = (d[:, 0] * e2[:, 1] - d[:, 1] * e2[:, 0]) / det
        b2 = (e1[:, 0] * d[:, 1] - e1[:, 1] * d[:, 0]) / det
        out = source[:, 0] + b1[:, None] * (source[:, 1] - source[:, 0]) + b2[:, None] * (source[:, 2] - source[:, 0])
        return out.astype(np.float32)
