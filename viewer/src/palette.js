// Colours: one hue per key, spread by the golden angle so neighbours in the
// list differ. Two-sided colouring: the positive side of a face gets the
// light shade, the negative side a dark shade of the same hue, so a wall's
// orientation is visible at a glance.
import * as THREE from 'three';

const GOLDEN = 0.618033988749895;

/** {front, back} THREE.Color (sRGB-specified) for entry i. */
export function shades(i) {
  const h = (0.07 + i * GOLDEN) % 1;
  return {
    front: new THREE.Color().setHSL(h, 0.7, 0.58, THREE.SRGBColorSpace),
    back: new THREE.Color().setHSL(h, 0.5, 0.36, THREE.SRGBColorSpace),
  };
}

/** Colour of cell i in the exploded view. */
export function cellColor(i) {
  const h = (0.37 + i * GOLDEN) % 1;
  return new THREE.Color().setHSL(h, 0.5, 0.62, THREE.SRGBColorSpace);
}

/** 0..255 sRGB triple of a colour, as it appears on screen unlit. */
export function rgb255(c) {
  const hex = c.getHex(THREE.SRGBColorSpace);
  return [(hex >> 16) & 255, (hex >> 8) & 255, hex & 255];
}
