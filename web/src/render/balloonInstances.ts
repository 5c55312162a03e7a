// The InstancedMesh every kind of balloon is drawn with (latex, foil): poses
// and tints are written into it every frame.

import * as THREE from "three";

/** An empty InstancedMesh of `capacity` balloons, its poses and tints written every frame. */
export function balloonInstances(
  geometry: THREE.BufferGeometry,
  material: THREE.Material,
  capacity: number,
  name: string,
): THREE.InstancedMesh {
  const mesh = new THREE.InstancedMesh(geometry, material, capacity);
  mesh.name = name;
  mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
  mesh.castShadow = true;
  mesh.receiveShadow = true;
  // Instances move every frame; culling by the base geometry's bounds would hide them.
  mesh.frustumCulled = false;
  mesh.count = 0;
  // Creates the colour attribute, so tints can be written from the first frame.
  mesh.setColorAt(0, new THREE.Color(1, 1, 1));
  return mesh;
}
