// The robot and its world from the MJCF's geoms (scene.geoms of the page): one THREE.Group per body slot (the
// moving bodies first, then the static ones), each geom a mesh at its local pose. MuJoCo's conventions: capsules
// and cylinders along the local z axis with (radius, half-length); boxes by half-extents; quaternions w, x, y, z.
import * as THREE from 'three';
import { float32, int32 } from './decode.js';

function meshGeometry(mesh) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(float32(mesh.vertices), 3));
  g.setIndex(new THREE.BufferAttribute(new Uint32Array(int32(mesh.faces)), 1));
  g.computeVertexNormals();
  return g;
}

function geometryOf(geom, meshes) {
  const s = geom.size;
  switch (geom.type) {
    case 'box': return new THREE.BoxGeometry(2 * s[0], 2 * s[1], 2 * s[2]);
    case 'sphere': return new THREE.SphereGeometry(s[0], 24, 16);
    case 'ellipsoid': return new THREE.SphereGeometry(1, 24, 16).scale(s[0], s[1], s[2]);
    case 'capsule': return new THREE.CapsuleGeometry(s[0], 2 * s[1], 6, 16).rotateX(Math.PI / 2);
    case 'cylinder': return new THREE.CylinderGeometry(s[0], s[0], 2 * s[1], 24).rotateX(Math.PI / 2);
    case 'mesh': return geom.mesh !== undefined ? meshGeometry(meshes[geom.mesh]) : null;
    default: return null;
  }
}

/**
 * The ground: 1 m checker squares as vertex colours under an unlit material. Software WebGL (headless Chromium
 * without a GPU) shades a lit or textured plane that fills half the view several times slower than the robot.
 */
function planeMesh(geom) {
  const hx = Math.min(geom.size[0] > 0 ? geom.size[0] : 20, 50), hy = Math.min(geom.size[1] > 0 ? geom.size[1] : 20, 50);
  const nx = Math.ceil(hx), ny = Math.ceil(hy);
  const positions = [], colors = [];
  const light = new THREE.Color(0xdde1e7), dark = new THREE.Color(0xc8cdd6);
  for (let i = -nx; i < nx; i++) {
    for (let j = -ny; j < ny; j++) {
      const x0 = Math.max(i, -hx), x1 = Math.min(i + 1, hx), y0 = Math.max(j, -hy), y1 = Math.min(j + 1, hy);
      positions.push(x0, y0, 0, x1, y0, 0, x1, y1, 0, x0, y0, 0, x1, y1, 0, x0, y1, 0);
      const c = (i + j) & 1 ? dark : light;
      for (let k = 0; k < 6; k++) colors.push(c.r, c.g, c.b);
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  g.setAttribute('color', new THREE.Float32BufferAttribute(colors, 3));
  const m = new THREE.Mesh(g, new THREE.MeshBasicMaterial({ vertexColors: true }));
  m.name = 'ground';
  return m;
}

export class RobotScene {
  /** `scene`: the page's scene object (bodies, moving, geoms, meshes). */
  constructor(scene) {
    this.moving = scene.moving;
    this.bodies = scene.bodies.map((name) => {
      const g = new THREE.Group();
      g.name = name;
      return g;
    });
    for (const geom of scene.geoms) {
      const mesh = geom.type === 'plane' ? planeMesh(geom) : this.geomMesh(geom, scene.meshes);
      if (!mesh) continue;
      mesh.position.set(geom.pos[0], geom.pos[1], geom.pos[2]);
      mesh.quaternion.set(geom.quat[1], geom.quat[2], geom.quat[3], geom.quat[0]);
      this.bodies[geom.slot].add(mesh);
    }
    this.root = new THREE.Group();
    this.robot = new THREE.Group();
    for (let i = 0; i < this.bodies.length; i++) (i < this.moving ? this.robot : this.root).add(this.bodies[i]);
    this.root.add(this.robot);
  }

  geomMesh(geom, meshes) {
    const geometry = geometryOf(geom, meshes);
    if (!geometry) return null;
    const [r, g, b, a] = geom.rgba;
    // Lambert shading: software WebGL (headless, no GPU) renders it several times faster than PBR.
    const material = new THREE.MeshLambertMaterial({
      color: new THREE.Color().setRGB(r, g, b, THREE.SRGBColorSpace), transparent: a < 1, opacity: a,
    });
    return new THREE.Mesh(geometry, material);
  }

  /** Pose of slot i from 7 values (x, y, z, qw, qx, qy, qz) of `values` at `offset`. */
  setPose(i, values, offset) {
    const b = this.bodies[i];
    b.position.set(values[offset], values[offset + 1], values[offset + 2]);
    b.quaternion.set(values[offset + 4], values[offset + 5], values[offset + 6], values[offset + 3]).normalize();
  }

  /** Static slots (the wall where this run had it, the ground) from 7 values per static slot. */
  setStatic(values) {
    for (let i = this.moving, j = 0; i < this.bodies.length && 7 * j + 6 < values.length; i++, j++) {
      this.setPose(i, values, 7 * j);
    }
  }
}
