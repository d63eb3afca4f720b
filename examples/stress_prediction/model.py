"""A small network predicting a grasped object's per-point von Mises stress from two point
clouds at the settled grasp: the object's vertices and the gripper's surface vertices.

  point encoders   per-point MLP, then layers of local kNN max pooling (each point takes the
                   max of its k nearest neighbours' features: PointNet++-style, CPU-cheap)
  cross-attention  object points attend to gripper points; the logits get a learned penalty
                   on the distance between the two points, so contact regions dominate
  head             per-object-point MLP to the stress in log scale: log1p(stress / 1 kPa)

The log scale: stress spans orders of magnitude over an object (contact patch to far side)
and over materials; a squared error on it weighs every decade alike, and the unit (1 kPa)
keeps near-zero stress near 0 instead of at -inf.
"""
import torch
from torch import nn

STRESS_UNIT = 1e3  # Pa


def stress_to_target(stress):
    return torch.log1p(stress.clamp(min=0) / STRESS_UNIT)


def target_to_stress(target):
    return STRESS_UNIT * torch.expm1(target).clamp(min=0)


def mlp(*sizes):
    layers = []
    for a, b in zip(sizes[:-1], sizes[1:]):
        layers += [nn.Linear(a, b), nn.GELU()]
    return nn.Sequential(*layers[:-1])


def knn(points, mask, k, chunk=2048):
    """(B, N, k) indices of each point's k nearest valid points (itself included); queries in
    chunks, so a large cloud needs chunk x N distances at a time, not N x N."""
    found = []
    for start in range(0, points.shape[1], chunk):
        distance = torch.cdist(points[:, start:start + chunk], points)
        distance = distance.masked_fill(~mask[:, None, :], float("inf"))
        found.append(distance.topk(min(k, points.shape[1]), dim=-1, largest=False).indices)
    return torch.cat(found, dim=1)


def gather(features, index):
    """features (B, N, C), index (B, N, k) -> (B, N, k, C)."""
    b, n, k = index.shape
    flat = index.reshape(b, n * k, 1).expand(-1, -1, features.shape[-1])
    return features.gather(1, flat).reshape(b, n, k, -1)


class PointEncoder(nn.Module):
    """Per-point features of a masked cloud: MLP, then rounds of local kNN max pooling."""

    def __init__(self, width, rounds=2, k=16):
        super().__init__()
        self.k = k
        self.embed = mlp(3, width, width)
        self.rounds = nn.ModuleList(mlp(2 * width, width, width) for _ in range(rounds))
        self.norms = nn.ModuleList(nn.LayerNorm(width) for _ in range(rounds))

    def forward(self, points, mask):
        neighbours = knn(points, mask, self.k)
        h = self.embed(points)
        for layer, norm in zip(self.rounds, self.norms):
            local = gather(h, neighbours).max(dim=2).values
            h = norm(h + layer(torch.cat([h, local], dim=-1)))
        return h


class CrossAttention(nn.Module):
    """Object points (queries) attend to gripper points (keys, values), multi-head, with a
    learned per-head penalty on their distance added to the logits."""

    def __init__(self, width, heads=4):
        super().__init__()
        self.heads, self.head_width = heads, width // heads
        self.query, self.key, self.value = (nn.Linear(width, width) for _ in range(3))
        self.out = nn.Linear(width, width)
        self.distance_scale = nn.Parameter(torch.zeros(heads))
        self.norm, self.norm_ff = nn.LayerNorm(width), nn.LayerNorm(width)
        self.feed_forward = mlp(width, 2 * width, width)

    def split(self, x):
        b, n, _ = x.shape
        return x.reshape(b, n, self.heads, self.head_width).transpose(1, 2)

    def forward(self, h, points, grip_h, grip_points, grip_mask):
        q = self.split(self.query(h))
        k, v = self.split(self.key(grip_h)), self.split(self.value(grip_h))
        logits = q @ k.transpose(-1, -2) / self.head_width ** 0.5
        distance = torch.cdist(points, grip_points)[:, None]  # (B, 1, N, G)
        penalty = nn.functional.softplus(self.distance_scale)[None, :, None, None]
        logits = logits - penalty * distance
        logits = logits.masked_fill(~grip_mask[:, None, None, :], float("-inf"))
        attended = (logits.softmax(dim=-1) @ v).transpose(1, 2).reshape(h.shape)
        h = self.norm(h + self.out(attended))
        return self.norm_ff(h + self.feed_forward(h))


class StressNet(nn.Module):
    """forward(object points, object mask, gripper points, gripper mask) -> (B, N) predicted
    log1p(stress / STRESS_UNIT) per object point. Points are in metres, world frame; the net
    centres them on the object's centroid and scales by its radius, and keeps the
    `gripper_points` gripper points nearest the object (the rest of a hand cannot touch it)."""

    def __init__(self, width=64, k=16, gripper_points=256, distance_unit=10.0):
        super().__init__()
        self.gripper_points = gripper_points
        self.distance_unit = distance_unit  # attention distances in radius / distance_unit
        self.object_encoder = PointEncoder(width, k=k)
        self.gripper_encoder = PointEncoder(width, k=k)
        self.attention = CrossAttention(width)
        self.head = mlp(width, width, 1)

    def normalize(self, points, mask, grip):
        weight = mask[..., None].float()
        centre = (points * weight).sum(1, keepdim=True) / weight.sum(1, keepdim=True)
        radius = ((points - centre).norm(dim=-1) * mask).amax(1).clamp(min=1e-6)[:, None, None]
        return (points - centre) / radius, (grip - centre) / radius

    def nearest_gripper(self, points, mask, grip, grip_mask):
        gap = torch.cdist(grip, points).masked_fill(~mask[:, None, :], float("inf")).amin(-1)
        gap = gap.masked_fill(~grip_mask, float("inf"))
        count = min(self.gripper_points, grip.shape[1])
        index = gap.topk(count, dim=1, largest=False).indices
        chosen = grip.gather(1, index[..., None].expand(-1, -1, 3))
        return chosen, grip_mask.gather(1, index)

    def forward(self, points, mask, grip, grip_mask):
        points, grip = self.normalize(points, mask, grip)
        grip, grip_mask = self.nearest_gripper(points, mask, grip, grip_mask)
        h = self.object_encoder(points, mask)
        grip_h = self.gripper_encoder(grip, grip_mask)
        h = self.attention(h, points * self.distance_unit, grip_h, grip * self.distance_unit,
                           grip_mask)
        return self.head(h).squeeze(-1)
