// Writes samples/jpeg_images.h: two small real JPEG files (baseline and progressive) of one 16 x 16
// colour pattern, for the JPEG texture tests and the JPEG conformance vector. Run by hand when they
// must change; the header is committed, so that neither CI nor the tests need a JPEG encoder:
//
//   NODE_PATH=.cache/node/node_modules node samples/make_jpeg_images.js > samples/jpeg_images.h
//
// The encoder is sharp (libvips with mozjpeg), installed with @gltf-transform/cli by scripts/setup.sh.
const sharp = require('sharp');

const size = 16;
const pixels = Buffer.alloc(size * size * 3);
for (let y = 0; y < size; ++y)
  for (let x = 0; x < size; ++x) {
    const i = (y * size + x) * 3;
    pixels[i] = Math.round((x * 255) / (size - 1));                 // red: left to right
    pixels[i + 1] = Math.round((y * 255) / (size - 1));             // green: top to bottom
    pixels[i + 2] = ((x >> 2) + (y >> 2)) % 2 ? 230 : 40;           // blue: 4 x 4 checker
  }

function array(name, bytes) {
  const lines = [];
  for (let i = 0; i < bytes.length; i += 16)
    lines.push('    ' + Array.from(bytes.subarray(i, i + 16), (b) => '0x' + b.toString(16).padStart(2, '0')).join(', ') + ',');
  return `inline const std::vector<uint8_t> ${name} = {\n${lines.join('\n')}\n};\n`;
}

(async () => {
  const image = () => sharp(pixels, { raw: { width: size, height: size, channels: 3 } });
  const baseline = await image().jpeg({ quality: 85, chromaSubsampling: '4:2:0', progressive: false }).toBuffer();
  const progressive = await image().jpeg({ quality: 85, chromaSubsampling: '4:2:0', progressive: true }).toBuffer();
  const v = sharp.versions;
  process.stdout.write(`// Two real JPEG files of one 16 x 16 RGB pattern (red rising left to right, green top to bottom,
// blue a 4 x 4 checker), quality 85, 4:2:0 chroma, no metadata. Made once by
// samples/make_jpeg_images.js with sharp ${v.sharp} (libvips ${v.vips}, mozjpeg ${v.mozjpeg}); the bytes are what
// is tested (carried byte for byte), so they are committed rather than regenerated. Do not edit by hand.
#pragma once

#include <cstdint>
#include <vector>

namespace ellicast::samples {

// Baseline (SOF0) JPEG, ${baseline.length} bytes.
${array('kJpegBaseline16', baseline)}
// Progressive (SOF2) JPEG of the same pattern, ${progressive.length} bytes.
${array('kJpegProgressive16', progressive)}
}  // namespace ellicast::samples
`);
})();
