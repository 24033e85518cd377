//! Uncompressed ("stored") ZIP archives, as `.npz` files and FMUs are: local headers and
//! data, the central directory and the end record (APPNOTE.TXT 6.3), dated 1980-01-01.

/// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320), as ZIP requires.
pub(crate) fn crc32(data: &[u8]) -> u32 {
    let table: Vec<u32> = (0..256u32)
        .map(|n| (0..8).fold(n, |c, _| if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 }))
        .collect();
    !data.iter().fold(!0u32, |c, &b| table[((c ^ b as u32) & 0xff) as usize] ^ (c >> 8))
}

/// The archive of `entries` (member name, content), in order, without compression.
pub(crate) fn stored_archive(entries: &[(String, Vec<u8>)]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut central = Vec::new();
    for (name, data) in entries {
        let (crc, size, offset) = (crc32(data), data.len() as u32, out.len() as u32);
        let common = |v: &mut Vec<u8>| {
            v.extend(20u16.to_le_bytes()); // version needed
            v.extend(0u16.to_le_bytes()); // flags
            v.extend(0u16.to_le_bytes()); // stored
            v.extend(0u16.to_le_bytes()); // time
            v.extend(0x21u16.to_le_bytes()); // date 1980-01-01
            v.extend(crc.to_le_bytes());
            v.extend(size.to_le_bytes());
            v.extend(size.to_le_bytes());
            v.extend((name.len() as u16).to_le_bytes());
            v.extend(0u16.to_le_bytes()); // extra length
        };
        out.extend(0x0403_4b50u32.to_le_bytes());
        common(&mut out);
        out.extend(name.as_bytes());
        out.extend(data);
        central.extend(0x0201_4b50u32.to_le_bytes());
        central.extend(20u16.to_le_bytes()); // version made by
        common(&mut central);
        central.extend([0u8; 8]); // comment length, disk, internal and external attributes
        central.extend([0u8; 2]);
        central.extend(offset.to_le_bytes());
        central.extend(name.as_bytes());
    }
    let (cd_offset, cd_size, n) = (out.len() as u32, central.len() as u32, entries.len() as u16);
    out.extend(central);
    out.extend(0x0605_4b50u32.to_le_bytes());
    out.extend([0u8; 4]);
    out.extend(n.to_le_bytes());
    out.extend(n.to_le_bytes());
    out.extend(cd_size.to_le_bytes());
    out.extend(cd_offset.to_le_bytes());
    out.extend(0u16.to_le_bytes());
    out
}

/// The members of a stored archive written by [`stored_archive`]: (name, content), read
/// back through the central directory (for tests and for checking an archive just written).
#[cfg(test)]
pub(crate) fn stored_members(b: &[u8]) -> Option<Vec<(String, Vec<u8>)>> {
    let u16_at = |i: usize| b.get(i..i + 2).map(|s| u16::from_le_bytes([s[0], s[1]]) as usize);
    let u32_at = |i: usize| b.get(i..i + 4).map(|s| u32::from_le_bytes([s[0], s[1], s[2], s[3]]) as usize);
    let end = b.len().checked_sub(22)?;
    if u32_at(end)? != 0x0605_4b50 {
        return None;
    }
    let (n, mut c) = (u16_at(end + 10)?, u32_at(end + 16)?);
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        if u32_at(c)? != 0x0201_4b50 {
            return None;
        }
        let (size, name_len, offset) = (u32_at(c + 24)?, u16_at(c + 28)?, u32_at(c + 42)?);
        let name = String::from_utf8(b.get(c + 46..c + 46 + name_len)?.to_vec()).ok()?;
        let local_name = u16_at(offset + 26)?;
        let start = offset + 30 + local_name + u16_at(offset + 28)?;
        out.push((name, b.get(start..start + size)?.to_vec()));
        c += 46 + name_len;
    }
    Some(out)
}
