// The planned template as a translucent ghost: waist box, four feet (wheel-centre spheres), the template's
// legs (lines from the waist origin to the feet) and the planned contact-force arrows.
import * as THREE from 'three';
import { Arrow } from './arrow.js';

const GHOST_COLOR = 0x2f6fd6;

export class Ghost {
  constructor() {
    const material = new THREE.MeshLambertMaterial({ color: GHOST_COLOR, transparent: true, opacity: 0.3, depthWrite: false });
    this.object = new THREE.Group();
    this.waist = new THREE.Mesh(new THREE.BoxGeometry(1, 1, 1), material);
    this.waist.add(new THREE.LineSegments(new THREE.EdgesGeometry(this.waist.geometry),
      new THREE.LineBasicMaterial({ color: GHOST_COLOR, transparent: true, opacity: 0.9 })));
    this.object.add(this.waist);
    this.feet = [];
    this.arrows = [];
    const legPositions = new Float32Array(4 * 2 * 3);
    this.legGeometry = new THREE.BufferGeometry();
    this.legGeometry.setAttribute('position', new THREE.BufferAttribute(legPositions, 3));
    this.legs = new THREE.LineSegments(this.legGeometry,
      new THREE.LineBasicMaterial({ color: GHOST_COLOR, transparent: true, opacity: 0.6 }));
    this.object.add(this.legs);
    for (let k = 0; k < 4; k++) {
      const foot = new THREE.Mesh(new THREE.SphereGeometry(1, 20, 12), material);
      this.feet.push(foot);
      this.object.add(foot);
      const arrow = new Arrow(GHOST_COLOR, 0.55);
      this.arrows.push(arrow);
      this.object.add(arrow.object);
    }
    this.object.visible = false;
    this.tail = new THREE.Vector3();
    this.dir = new THREE.Vector3();
  }

  /** Shape for a plan: waist half extents [m] and foot radius [m]. */
  configure(ghost) {
    const h = ghost.waist_half_extents;
    this.waist.scale.set(2 * h[0] || 0.6, 2 * h[1] || 0.34, 2 * h[2] || 0.11);
    for (const f of this.feet) f.scale.setScalar(ghost.foot_radius);
    this.radius = ghost.foot_radius;
  }

  /** Pose from 31 values (waist p 3, q w,x,y,z 4, feet 12, forces 12) at `o`; `scale` [m/N] for the arrows. */
  set(v, o, scale, showForces) {
    this.waist.position.set(v[o], v[o + 1], v[o + 2]);
    this.waist.quaternion.set(v[o + 4], v[o + 5], v[o + 6], v[o + 3]).normalize();
    const legs = this.legGeometry.attributes.position;
    for (let k = 0; k < 4; k++) {
      const p = o + 7 + 3 * k, f = o + 19 + 3 * k;
      this.feet[k].position.set(v[p], v[p + 1], v[p + 2]);
      legs.setXYZ(2 * k, v[o], v[o + 1], v[o + 2]);
      legs.setXYZ(2 * k + 1, v[p], v[p + 1], v[p + 2]);
      const norm = Math.hypot(v[f], v[f + 1], v[f + 2]);
      if (!showForces || norm < 1.0) {  // a foot planned in flight has no force
        this.arrows[k].set(this.tail, this.dir, 0);
        continue;
      }
      this.dir.set(v[f] / norm, v[f + 1] / norm, v[f + 2] / norm);
      this.tail.set(v[p], v[p + 1], v[p + 2]).addScaledVector(this.dir, -this.radius);
      this.arrows[k].set(this.tail, this.dir, norm * scale);
    }
    legs.needsUpdate = true;
  }
}
