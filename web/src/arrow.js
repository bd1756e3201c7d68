// A solid 3D arrow (shaft + head) for contact forces: tail at a point, along a direction, length in metres.
import * as THREE from 'three';

const shaftGeometry = new THREE.CylinderGeometry(1, 1, 1, 12).translate(0, 0.5, 0);
const headGeometry = new THREE.ConeGeometry(1, 1, 16).translate(0, 0.5, 0);
const up = new THREE.Vector3(0, 1, 0);

export class Arrow {
  constructor(color, opacity = 1.0) {
    const material = new THREE.MeshBasicMaterial({
      color, transparent: true, opacity, depthTest: false, depthWrite: false,
    });
    this.shaft = new THREE.Mesh(shaftGeometry, material);
    this.head = new THREE.Mesh(headGeometry, material);
    this.object = new THREE.Group();
    this.object.add(this.shaft, this.head);
    this.object.renderOrder = 10;
    this.shaft.renderOrder = 10;
    this.head.renderOrder = 10;
    this.object.visible = false;
  }

  /** Tail at `tail` (Vector3), pointing along `dir` (unit Vector3), total length `length` [m]. */
  set(tail, dir, length) {
    if (!(length > 1e-4)) {
      this.object.visible = false;
      return;
    }
    const head = Math.min(0.08, 0.5 * length);
    const radius = 0.012;
    this.object.visible = true;
    this.object.position.copy(tail);
    this.object.quaternion.setFromUnitVectors(up, dir);
    this.shaft.scale.set(radius, length - head, radius);
    this.head.position.set(0, length - head, 0);
    this.head.scale.set(2.8 * radius, head, 2.8 * radius);
  }
}
